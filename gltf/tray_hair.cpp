#include "gltf/tray_hair.h"

#include <algorithm>
#include <cmath>

#include "gltf/gltf_value.h"
#include "materials/hair_lobe.h"

namespace tray {

void readHairMaterial(const GltfContext& ctx, const tinygltf::Value& ext, const std::string& where,
                      Material& m) {
  ExtensionReader r(ctx, ext, where + " TRAY_materials_hair");
  HairParams& h = m.hair;
  h.enabled = true;
  h.betaM = float(r.number("roughness", 0.3, 0.001, 1.0));
  h.betaN = float(r.number("azimuthalRoughness", 0.3, 0.001, 1.0));
  h.ior = float(r.number("ior", 1.55, 1.0, 4.0));
  h.alpha = float(r.number("cuticleAngle", 2.0, -30.0, 30.0));
  const bool melanin = r.has("melanin") || r.has("melaninRedness");
  const int ways = int(melanin) + int(r.has("color")) + int(r.has("absorptionCoefficient"));
  if (ways > 1) r.fail("give one of 'melanin'/'melaninRedness', 'color', 'absorptionCoefficient'");
  if (r.has("color")) {
    // Chiang et al. 2016 eq. 9: the absorption that gives this colour after multiple scattering.
    h.sigmaA = HairLobe::sigmaAFromReflectance(r.vec3("color", Color(1.0f), 0.0, 1.0), h.betaN);
  } else if (r.has("absorptionCoefficient")) {
    h.sigmaA = r.vec3("absorptionCoefficient", Color(0.0f), 0.0, 1e4);
  } else {
    // Cycles' principled hair: melanin in [0, 1] mapped to a concentration -ln(1 - melanin)
    // (perceptually even), split between eumelanin and pheomelanin by the redness.
    const float amount = float(r.number("melanin", 0.8, 0.0, 1.0));
    const float redness = float(r.number("melaninRedness", 1.0, 0.0, 1.0));
    const float c = -std::log(std::max(1.0f - amount, 1e-4f));
    h.sigmaA = HairLobe::sigmaAFromConcentration(c * (1 - redness), c * redness);
  }
  r.finish();
  // Whitted and the PBR fallbacks see a rough dielectric of the hair's single-scattering
  // colour: a diffuse stand-in (the hair BSDF is for the physically based integrators).
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.transmission = 0.0f;
  m.baseColor = {std::exp(-h.sigmaA.x), std::exp(-h.sigmaA.y), std::exp(-h.sigmaA.z)};
}

}  // namespace tray

#include "core/material.h"

namespace tray {

ShadingMaterial ShadingMaterial::of(const Material& m, const Vec3& n) {
  ShadingMaterial s;
  s.baseColor = m.baseColor;
  s.metallic = m.metallic;
  s.roughness = m.roughness;
  s.emissive = m.emissive;
  s.transmission = m.transmission;
  s.ior = m.ior;
  s.unlit = m.unlit;
  s.specular = m.layers.specular;
  s.specularColor = m.layers.specularColor;
  s.clearcoat = m.layers.clearcoat;
  s.clearcoatRoughness = m.layers.clearcoatRoughness;
  s.sheenColor = m.layers.sheenColor;
  s.sheenRoughness = m.layers.sheenRoughness;
  s.anisotropy = m.layers.anisotropyStrength;
  s.diffuseTransmission = m.layers.diffuseTransmission;
  s.diffuseTransmissionColor = m.layers.diffuseTransmissionColor;
  s.iridescence = m.layers.iridescence;
  s.iridescenceIor = m.layers.iridescenceIor;
  s.iridescenceThickness = m.layers.iridescenceThicknessMax;
  s.phong = m.phong;
  s.n = n;
  s.clearcoatN = n;
  s.hair = m.hair.enabled ? &m.hair : nullptr;
  return s;
}

PhongParams phongFromPbr(const Material& m) {
  PhongParams p = phongFromPbr(m.baseColor, m.metallic, m.roughness, m.transmission);
  const MaterialLayers& l = m.layers;
  phongLayers(p, m.baseColor, m.metallic, l.specular, l.specularColor, l.clearcoat,
              l.clearcoatRoughness);
  return p;
}

void phongLayers(PhongParams& p, const Color& baseColor, float metallic, float specular,
                 const Color& specularColor, float clearcoat, float clearcoatRoughness) {
  // KHR_materials_specular scales and tints the dielectric's 4% white specular; metals keep
  // theirs. Untouched when the extension is at its defaults (bit-identical images).
  if (specular != 1.0f || !(specularColor == Color(1.0f))) {
    const Color dielectric = min(Color(0.04f) * specularColor, Color(1.0f)) * specular;
    p.specular = dielectric * (1.0f - metallic) + baseColor * metallic;
  }
  // KHR_materials_clearcoat: the coat's 4% mirror reflection, faded by its roughness like the
  // metal mirror term above, added to what the base already reflects.
  if (clearcoat > 0) {
    const float smooth = 1.0f - clearcoatRoughness;
    p.reflectance += (1.0f - p.reflectance) * clearcoat * 0.04f * smooth * smooth;
  }
}

PhongParams phongFromPbr(const Color& baseColor, float metallic, float roughness,
                         float transmission) {
  // Dielectrics keep their base color as diffuse and a white 4% specular; metals put the base
  // color into the specular and the mirror term. Smoothness maps to the Phong exponent through
  // the usual Blinn-Phong/Beckmann correspondence shininess = 2 / alpha^2 - 2 with alpha =
  // roughness^2 (Walter et al. 2007, eq. 30).
  PhongParams p;
  float alpha = std::max(roughness * roughness, 1e-3f);
  p.shininess = std::min(2.0f / (alpha * alpha) - 2.0f, 1e4f);
  float dielectric = 1.0f - metallic;
  p.diffuse = baseColor * (dielectric * (1.0f - transmission));
  p.specular = Color(0.04f) * dielectric + baseColor * metallic;
  float smooth = 1.0f - roughness;
  p.reflectance = metallic * smooth * smooth;
  // The mirror term is the metal's: a metal's Fresnel reflectance at normal incidence is its
  // base colour (glTF 2.0 appendix B, conductor_fresnel), so a red metal reflects red.
  p.mirrorF0 = baseColor;
  p.transmittance = transmission * dielectric;
  p.ambient = p.diffuse;  // ambient light is reflected like diffuse light
  return p;
}

}  // namespace tray

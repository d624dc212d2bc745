#pragma once
#include <algorithm>
#include <cmath>
#include <string>

#include "core/math.h"

namespace tray {

/// How a texture repeats outside [0, 1] (glTF 2.0 §3.8.4.3, sampler wrapS / wrapT).
enum class TextureWrap { kRepeat, kClampToEdge, kMirroredRepeat };

/// glTF sampler filters (§3.8.4.2). Magnification uses only kNearest / kLinear; a minification
/// filter names the texel filter, then the MIP-level choice (kLinearMipmapLinear = trilinear).
enum class TextureFilter {
  kNearest,
  kLinear,
  kNearestMipmapNearest,
  kLinearMipmapNearest,
  kNearestMipmapLinear,
  kLinearMipmapLinear
};

/// A texture reference of a material: which image, which uv set, how it is sampled, and its
/// KHR_texture_transform. image = -1: no texture.
struct TextureRef {
  int image = -1;  ///< index into Scene::textures
  int texCoord = 0;
  float scale = 1.0f;  ///< normal scale / occlusion strength
  TextureWrap wrapS = TextureWrap::kRepeat, wrapT = TextureWrap::kRepeat;
  TextureFilter magFilter = TextureFilter::kLinear;
  TextureFilter minFilter = TextureFilter::kLinearMipmapLinear;  ///< glTF leaves it open
  // KHR_texture_transform
  Vec2 offset{0, 0};
  Vec2 scaleUV{1, 1};
  float rotation = 0;
  bool valid() const { return image >= 0; }
};

/// glTF 2.0 §3.9.4 "Alpha Coverage": how base-colour alpha is read (docs/scene-format.md, "Alpha").
enum class AlphaMode { kOpaque, kMask, kBlend };

/// The seed's Phong model, stated by TRAY_materials_phong or derived from the PBR factors
/// (see docs/scene-format.md for the mapping).
struct PhongParams {
  Color ambient{0.0f};
  Color diffuse{0.8f};
  Color specular{0.0f};
  float shininess = 32.0f;
  float reflectance = 0.0f;    ///< kr
  /// Normal-incidence colour of the mirror term, Fresnel-Schlick weighted by Whitted: the base
  /// colour of a metal (derived mapping), white for a stated TRAY_materials_phong kr.
  Color mirrorF0{1.0f};
  float transmittance = 0.0f;  ///< kt
};

/// The layered-material extensions (docs/path-tracing.md, "Material layers"). Defaults leave a
/// material exactly as plain metallic-roughness renders it.
struct MaterialLayers {
  // KHR_materials_volume. thickness is stored but not used: TRay traces the real geometry, so
  // the distance travelled inside is known (the extension offers thickness for rasterisers).
  float thickness = 0.0f;
  Color attenuationColor{1.0f};
  float attenuationDistance = kInfinity;
  // TRAY_materials_scattering (docs/subsurface.md): the volume also scatters, a homogeneous
  // medium of scattering coefficient sigma_s (per channel, per scene unit) and
  // Henyey-Greenstein anisotropy g; its absorption is the volume's sigma_a above.
  bool scatteringMedium = false;
  Color scattering{0.0f};
  float scatterAnisotropy = 0.0f;
  // KHR_materials_specular: weight and F0 tint of the dielectric specular reflection.
  float specular = 1.0f;
  Color specularColor{1.0f};
  // KHR_materials_clearcoat: a GGX dielectric coat (IOR 1.5) over the whole material.
  float clearcoat = 0.0f;
  float clearcoatRoughness = 0.0f;
  // KHR_materials_sheen: Charlie sheen over the base; black = off.
  Color sheenColor{0.0f};
  float sheenRoughness = 0.0f;
  // KHR_materials_anisotropy: GGX stretched along a direction in the tangent plane.
  float anisotropyStrength = 0.0f;
  float anisotropyRotation = 0.0f;  ///< radians, counter-clockwise from the tangent
  // KHR_materials_diffuse_transmission: Lambert transmission mixed into the diffuse base.
  float diffuseTransmission = 0.0f;
  Color diffuseTransmissionColor{1.0f};
  /// anisotropyTexture (RG direction in tangent space, B strength; linear),
  /// diffuseTransmissionTexture (A), diffuseTransmissionColorTexture (RGB, sRGB).
  TextureRef anisotropyTexture, diffuseTransmissionTexture, diffuseTransmissionColorTexture;
  /// specularTexture (A), specularColorTexture (RGB, sRGB), clearcoatTexture (R),
  /// clearcoatRoughnessTexture (G), clearcoatNormalTexture: multiplied into the factors.
  /// sheenColorTexture (RGB, sRGB), sheenRoughnessTexture (A).
  TextureRef specularTexture, specularColorTexture, clearcoatTexture, clearcoatRoughnessTexture,
      clearcoatNormalTexture, sheenColorTexture, sheenRoughnessTexture;
  // KHR_materials_iridescence (docs/materials-iridescence-dispersion.md): a thin film over the
  // GGX reflection; factor 0 = off. Thickness in nanometres: thicknessMaximum without a
  // texture, else mix(minimum, maximum, texture G). iridescenceTexture (R) scales the factor.
  float iridescence = 0.0f, iridescenceIor = 1.3f;
  float iridescenceThicknessMin = 100.0f, iridescenceThicknessMax = 400.0f;
  TextureRef iridescenceTexture, iridescenceThicknessTexture;
  // KHR_materials_dispersion: 20 / Abbe number of the transmissive volume; 0 = none.
  float dispersion = 0.0f;
  bool hasTextures() const {
    return specularTexture.valid() || specularColorTexture.valid() || clearcoatTexture.valid() ||
           clearcoatRoughnessTexture.valid() || clearcoatNormalTexture.valid() ||
           sheenColorTexture.valid() || sheenRoughnessTexture.valid() ||
           anisotropyTexture.valid() || diffuseTransmissionTexture.valid() ||
           diffuseTransmissionColorTexture.valid() ||
           iridescenceTexture.valid() || iridescenceThicknessTexture.valid();
  }

  /// Beer-Lambert absorption coefficient sigma_a = -ln(attenuationColor) / attenuationDistance
  /// per channel (KHR_materials_volume); 0 where nothing is absorbed. A zero colour channel is
  /// read as 1e-30 so that sigma_a stays finite (exp(-sigma_a t) is then 0 for any t > 0).
  Color absorption() const {
    if (!(attenuationDistance < kInfinity)) return Color(0.0f);
    auto one = [&](float c) { return -std::log(std::max(c, 1e-30f)) / attenuationDistance; };
    return {one(attenuationColor.x), one(attenuationColor.y), one(attenuationColor.z)};
  }
  bool hasSpecular() const { return specular != 1.0f || !(specularColor == Color(1.0f)); }
};

/// TRAY_materials_hair (docs/curves-subdivision.md): Chiang et al. 2016's hair BSDF
/// (materials/hair_bsdf.h) instead of the glTF lobes. sigmaA is per unit fibre radius, already
/// derived from melanin or colour by the glTF reader.
struct HairParams {
  bool enabled = false;
  Color sigmaA{0.0f};
  float betaM = 0.3f;  ///< longitudinal roughness, (0, 1]
  float betaN = 0.3f;  ///< azimuthal roughness, (0, 1]
  float ior = 1.55f;   ///< of the fibre (keratin)
  float alpha = 2.0f;  ///< cuticle scale tilt, degrees
};

/// One material, holding both the glTF metallic-roughness description (used by physically
/// based integrators) and the Phong parameters (used by Whitted). Defaults are glTF's.
struct Material {
  std::string name;
  Color baseColor{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;
  Color emissive{0.0f};  ///< emissiveFactor x KHR_materials_emissive_strength
  float transmission = 0.0f;
  float ior = 1.5f;
  bool doubleSided = false;
  int priority = 0;  ///< nested-dielectric priority (TRAY_materials_priority)
  AlphaMode alphaMode = AlphaMode::kOpaque;
  float alpha = 1.0f;        ///< baseColorFactor's alpha (read only when not kOpaque)
  float alphaCutoff = 0.5f;  ///< kMask: alpha below it is cut out
  bool unlit = false;        ///< KHR_materials_unlit: shows base colour, no lighting
  MaterialLayers layers;  ///< KHR_materials_volume / specular / clearcoat / sheen
  PhongParams phong;
  /// TRAY_materials_hair; enabled: the hair BSDF replaces everything above.
  HairParams hair;
  bool hasPhong = false;  ///< phong came from TRAY_materials_phong rather than the mapping
  TextureRef baseColorTexture, metallicRoughnessTexture, emissiveTexture, normalTexture;
  bool hasTextures() const {
    return baseColorTexture.valid() || metallicRoughnessTexture.valid() ||
           emissiveTexture.valid() || normalTexture.valid() || layers.hasTextures();
  }
};

/// A material's parameters at one surface point: factors times texture values.
struct ShadingMaterial {
  Color baseColor{1.0f};
  float metallic = 1.0f, roughness = 1.0f;
  Color emissive{0.0f};
  float transmission = 0.0f, ior = 1.5f;
  float alpha = 1.0f;  ///< coverage of an alphaMode BLEND surface (1 otherwise)
  float specular = 1.0f;  ///< KHR_materials_specular (factor x texture alpha)
  Color specularColor{1.0f};
  float clearcoat = 0.0f, clearcoatRoughness = 0.0f;  ///< KHR_materials_clearcoat
  /// The coat's normal: the interpolated normal, or clearcoatNormalTexture's; never the base's
  /// normalTexture (KHR_materials_clearcoat, "Clearcoat normal").
  Vec3 clearcoatN;
  Color sheenColor{0.0f};  ///< KHR_materials_sheen
  float sheenRoughness = 0.0f;
  /// KHR_materials_anisotropy: strength (factor x texture blue) and the direction of the
  /// stretched roughness, world-space, perpendicular to n (set wherever anisotropy > 0).
  float anisotropy = 0.0f;
  Vec3 anisotropyDirection;
  /// KHR_materials_diffuse_transmission (factor x texture alpha; colour factor x texture).
  float diffuseTransmission = 0.0f;
  Color diffuseTransmissionColor{1.0f};
  /// KHR_materials_iridescence: factor (x texture R), film IOR, film thickness in nm.
  float iridescence = 0.0f, iridescenceIor = 1.3f, iridescenceThickness = 400.0f;
  bool unlit = false;  ///< KHR_materials_unlit: baseColor is the outgoing radiance
  PhongParams phong;
  Vec3 n;  ///< shading normal, normal map applied; on the same side as SurfacePoint::n
  /// TRAY_materials_hair: the material's hair parameters (null: not hair) and the fibre's
  /// direction there (SurfacePoint::tangent; zero off curves).
  const HairParams* hair = nullptr;
  Vec3 tangent;

  /// The untextured material at a point with shading normal n.
  static ShadingMaterial of(const Material& m, const Vec3& n);
};

/// Phong parameters derived from a PBR material (documented in docs/scene-format.md).
PhongParams phongFromPbr(const Material& m);
/// Whitted's share of KHR_materials_specular (ks of dielectrics scaled and tinted) and
/// KHR_materials_clearcoat (a 4% mirror reflectance added); no change at their defaults.
void phongLayers(PhongParams& p, const Color& baseColor, float metallic, float specular,
                 const Color& specularColor, float clearcoat, float clearcoatRoughness);
/// The same from the factors alone (for textured values at a surface point).
PhongParams phongFromPbr(const Color& baseColor, float metallic, float roughness,
                         float transmission);

}  // namespace tray

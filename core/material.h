#pragma once
#include <string>

#include "core/math.h"

namespace tray {

/// A texture reference (filled by the texture work; -1 = none).
struct TextureRef {
  int image = -1;  ///< index into Scene::textures
  int texCoord = 0;
  float scale = 1.0f;  ///< normal scale / occlusion strength
  // KHR_texture_transform
  Vec2 offset{0, 0};
  Vec2 scaleUV{1, 1};
  float rotation = 0;
};

/// The seed's Phong model, stated by TRAY_materials_phong or derived from the PBR factors
/// (see docs/scene-format.md for the mapping).
struct PhongParams {
  Color ambient{0.0f};
  Color diffuse{0.8f};
  Color specular{0.0f};
  float shininess = 32.0f;
  float reflectance = 0.0f;    ///< kr
  float transmittance = 0.0f;  ///< kt
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
  PhongParams phong;
  bool hasPhong = false;  ///< phong came from TRAY_materials_phong rather than the mapping
  TextureRef baseColorTexture, metallicRoughnessTexture, emissiveTexture, normalTexture;
};

/// Phong parameters derived from a PBR material (documented in docs/scene-format.md).
PhongParams phongFromPbr(const Material& m);

}  // namespace tray

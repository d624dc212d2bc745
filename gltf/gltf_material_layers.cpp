#include "gltf/gltf_material_layers.h"

#include "gltf/gltf_materials.h"
#include "gltf/gltf_value.h"

namespace tray {

namespace {

/// A textureInfo inside an extension object (glTF 2.0 §5.22: index, texCoord, and for normal
/// textures scale), with its KHR_texture_transform.
TextureRef readTextureInfo(const GltfContext& ctx, ExtensionReader& parent, const char* key,
                           const std::string& where) {
  TextureRef ref;
  const tinygltf::Value* v = parent.value(key);
  if (!v) return ref;
  const std::string here = where + " " + key;
  ExtensionReader r(ctx, *v, here);
  const int index = r.integer("index", -1);
  if (index < 0 || size_t(index) >= ctx.model.textures.size())
    r.fail("refers to missing texture " + std::to_string(index));
  ref.image = index;
  ref.texCoord = r.integer("texCoord", 0);
  if (ref.texCoord < 0) r.fail("has a negative texCoord");
  ref.scale = float(r.number("scale", 1.0));
  if (const tinygltf::Value* ext = r.value("extensions"); ext && ext->Has("KHR_texture_transform"))
    readTextureTransform(ctx, ext->Get("KHR_texture_transform"), here, ref);
  return ref;
}

}  // namespace

void readMaterialLayers(const GltfContext& ctx, const tinygltf::Material& g,
                        const std::string& where, Material& m) {
  MaterialLayers& l = m.layers;
  const auto& ext = g.extensions;
  if (const auto* e = findExtension(ext, "KHR_materials_volume")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_volume");
    l.thickness = float(r.number("thicknessFactor", 0.0, 0.0));
    l.attenuationColor = r.vec3("attenuationColor", l.attenuationColor, 0.0, 1.0);
    // The extension's default distance is +infinity: no absorption. 0 is not a distance.
    l.attenuationDistance = float(r.number("attenuationDistance", kInfinity, 0.0));
    if (!(l.attenuationDistance > 0)) r.fail("'attenuationDistance' must be positive");
    // thicknessTexture is read nowhere: TRay traces the real geometry (see MaterialLayers).
  }
  if (const auto* e = findExtension(ext, "KHR_materials_anisotropy")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_anisotropy");
    l.anisotropyStrength = float(r.number("anisotropyStrength", 0.0, 0.0, 1.0));
    l.anisotropyRotation = float(r.number("anisotropyRotation", 0.0));
    l.anisotropyTexture = readTextureInfo(ctx, r, "anisotropyTexture", r.where());
  }
  if (const auto* e = findExtension(ext, "KHR_materials_diffuse_transmission")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_diffuse_transmission");
    l.diffuseTransmission = float(r.number("diffuseTransmissionFactor", 0.0, 0.0, 1.0));
    l.diffuseTransmissionColor =
        r.vec3("diffuseTransmissionColorFactor", l.diffuseTransmissionColor, 0.0, 1.0);
    l.diffuseTransmissionTexture = readTextureInfo(ctx, r, "diffuseTransmissionTexture", r.where());
    l.diffuseTransmissionColorTexture =
        readTextureInfo(ctx, r, "diffuseTransmissionColorTexture", r.where());
  }
  if (const auto* e = findExtension(ext, "TRAY_materials_scattering")) {
    // docs/subsurface.md: the volume scatters; its boundary must be a dielectric to enter.
    ExtensionReader r(ctx, *e, where + " TRAY_materials_scattering");
    l.scatteringMedium = true;
    l.scattering = r.vec3("scatteringCoefficient", l.scattering, 0.0);
    l.scatterAnisotropy = float(r.number("anisotropy", 0.0, -0.99, 0.99));
    r.finish();
    if (!(m.transmission > 0)) r.fail("needs KHR_materials_transmission (a dielectric boundary)");
  }
  if (const auto* e = findExtension(ext, "KHR_materials_specular")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_specular");
    l.specular = float(r.number("specularFactor", 1.0, 0.0, 1.0));
    // Colours above 1 are allowed by the extension (F0 is clamped to 1 after the IOR factor).
    l.specularColor = r.vec3("specularColorFactor", l.specularColor, 0.0);
    l.specularTexture = readTextureInfo(ctx, r, "specularTexture", r.where());
    l.specularColorTexture = readTextureInfo(ctx, r, "specularColorTexture", r.where());
  }
  if (const auto* e = findExtension(ext, "KHR_materials_clearcoat")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_clearcoat");
    l.clearcoat = float(r.number("clearcoatFactor", 0.0, 0.0, 1.0));
    l.clearcoatRoughness = float(r.number("clearcoatRoughnessFactor", 0.0, 0.0, 1.0));
    l.clearcoatTexture = readTextureInfo(ctx, r, "clearcoatTexture", r.where());
    l.clearcoatRoughnessTexture = readTextureInfo(ctx, r, "clearcoatRoughnessTexture", r.where());
    l.clearcoatNormalTexture = readTextureInfo(ctx, r, "clearcoatNormalTexture", r.where());
  }
  if (const auto* e = findExtension(ext, "KHR_materials_sheen")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_sheen");
    l.sheenColor = r.vec3("sheenColorFactor", l.sheenColor, 0.0, 1.0);
    l.sheenRoughness = float(r.number("sheenRoughnessFactor", 0.0, 0.0, 1.0));
    l.sheenColorTexture = readTextureInfo(ctx, r, "sheenColorTexture", r.where());
    l.sheenRoughnessTexture = readTextureInfo(ctx, r, "sheenRoughnessTexture", r.where());
  }
  if (const auto* e = findExtension(ext, "KHR_materials_iridescence")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_iridescence");
    l.iridescence = float(r.number("iridescenceFactor", 0.0, 0.0, 1.0));
    l.iridescenceIor = float(r.number("iridescenceIor", 1.3, 1.0));
    l.iridescenceThicknessMin = float(r.number("iridescenceThicknessMinimum", 100.0, 0.0));
    l.iridescenceThicknessMax = float(r.number("iridescenceThicknessMaximum", 400.0, 0.0));
    l.iridescenceTexture = readTextureInfo(ctx, r, "iridescenceTexture", r.where());
    l.iridescenceThicknessTexture =
        readTextureInfo(ctx, r, "iridescenceThicknessTexture", r.where());
  }
  if (const auto* e = findExtension(ext, "KHR_materials_dispersion")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_dispersion");
    l.dispersion = float(r.number("dispersion", 0.0, 0.0));
  }
}

}  // namespace tray

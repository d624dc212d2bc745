#include "gltf/gltf_materials.h"

#include <cmath>

#include "gltf/gltf_material_layers.h"
#include "gltf/gltf_value.h"
#include "gltf/tray_hair.h"

namespace tray {

namespace {

/// In [lo, hi] and finite in single precision, which TRay stores material factors in.
bool finiteIn(double v, double lo, double hi) {
  return std::isfinite(float(v)) && v >= lo && v <= hi;
}

template <typename Info>
TextureRef readTexture(const GltfContext& ctx, const Info& info, const std::string& where) {
  TextureRef ref;
  if (info.index == -1) return ref;
  if (info.index < 0 || size_t(info.index) >= ctx.model.textures.size())
    ctx.fail(where + " refers to missing texture " + std::to_string(info.index));
  if (info.texCoord < 0) ctx.fail(where + " has a negative texCoord");
  // Image decoding comes later (textures work): the reference keeps the glTF texture index.
  ref.image = info.index;
  ref.texCoord = info.texCoord;
  if (const tinygltf::Value* t = findExtension(info.extensions, "KHR_texture_transform"))
    readTextureTransform(ctx, *t, where, ref);
  return ref;
}

/// TRAY_materials_phong: the Phong parameters stated outright; absent fields keep
/// PhongParams' defaults (docs/scene-format.md).
PhongParams readPhong(const GltfContext& ctx, const tinygltf::Value& ext,
                      const std::string& where) {
  ExtensionReader r(ctx, ext, where + " TRAY_materials_phong");
  PhongParams p;
  p.ambient = r.vec3("ambient", p.ambient, 0.0);
  p.diffuse = r.vec3("diffuse", p.diffuse, 0.0);
  p.specular = r.vec3("specular", p.specular, 0.0);
  p.shininess = float(r.number("shininess", p.shininess, 0.0));
  p.reflectance = float(r.number("reflectance", p.reflectance, 0.0, 1.0));
  p.transmittance = float(r.number("transmittance", p.transmittance, 0.0, 1.0));
  r.finish();
  return p;
}

/// alphaMode, alphaCutoff and baseColorFactor's alpha (glTF 2.0 §3.9.4, §5.19): OPAQUE ignores
/// alpha altogether; alphaCutoff matters for MASK only.
void readAlpha(const GltfContext& ctx, const tinygltf::Material& g, const std::string& where,
               Material& m) {
  if (g.alphaMode == "OPAQUE") {
    m.alphaMode = AlphaMode::kOpaque;
  } else if (g.alphaMode == "MASK") {
    m.alphaMode = AlphaMode::kMask;
  } else if (g.alphaMode == "BLEND") {
    m.alphaMode = AlphaMode::kBlend;
  } else {
    ctx.fail(where + " alphaMode '" + g.alphaMode + "' is not OPAQUE, MASK or BLEND");
  }
  // Finite in single precision, which TRay stores it in: 1e40 is finite only as a double.
  if (!(g.alphaCutoff >= 0) || !std::isfinite(float(g.alphaCutoff)))
    ctx.fail(where + " alphaCutoff is negative or not finite in single precision");
  m.alphaCutoff = float(g.alphaCutoff);
  m.alpha = float(g.pbrMetallicRoughness.baseColorFactor[3]);
}

}  // namespace

void readTextureTransform(const GltfContext& ctx, const tinygltf::Value& transform,
                          const std::string& where, TextureRef& ref) {
  ExtensionReader r(ctx, transform, where + " KHR_texture_transform");
  float offset[2] = {0, 0}, scale[2] = {1, 1};
  r.numbers("offset", offset, 2);
  r.numbers("scale", scale, 2);
  ref.offset = {offset[0], offset[1]};
  ref.scaleUV = {scale[0], scale[1]};
  ref.rotation = float(r.number("rotation", 0.0));
  ref.texCoord = r.integer("texCoord", ref.texCoord);
  if (ref.texCoord < 0) r.fail("'texCoord' is negative");
}

Material defaultGltfMaterial() {
  Material m;  // Material's defaults are glTF's
  m.name = "default";
  m.phong = phongFromPbr(m);
  return m;
}

Material convertMaterial(const GltfContext& ctx, int index) {
  const tinygltf::Material& g = ctx.model.materials[size_t(index)];
  const std::string where = nameOf("material", index, g.name);
  Material m;
  m.name = g.name;
  const auto& pbr = g.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() != 4) ctx.fail(where + " baseColorFactor needs 4 numbers");
  for (double v : pbr.baseColorFactor)
    if (!finiteIn(v, 0, 1)) ctx.fail(where + " baseColorFactor is outside [0, 1]");
  m.baseColor = {float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                 float(pbr.baseColorFactor[2])};
  readAlpha(ctx, g, where, m);
  if (!finiteIn(pbr.metallicFactor, 0, 1)) ctx.fail(where + " metallicFactor is outside [0, 1]");
  if (!finiteIn(pbr.roughnessFactor, 0, 1)) ctx.fail(where + " roughnessFactor is outside [0, 1]");
  m.metallic = float(pbr.metallicFactor);
  m.roughness = float(pbr.roughnessFactor);
  if (!g.emissiveFactor.empty()) {
    if (g.emissiveFactor.size() != 3) ctx.fail(where + " emissiveFactor needs 3 numbers");
    for (double v : g.emissiveFactor)
      if (!finiteIn(v, 0, 1)) ctx.fail(where + " emissiveFactor is outside [0, 1]");
    m.emissive = {float(g.emissiveFactor[0]), float(g.emissiveFactor[1]),
                  float(g.emissiveFactor[2])};
  }
  m.doubleSided = g.doubleSided;
  m.baseColorTexture = readTexture(ctx, pbr.baseColorTexture, where + " baseColorTexture");
  m.metallicRoughnessTexture =
      readTexture(ctx, pbr.metallicRoughnessTexture, where + " metallicRoughnessTexture");
  m.emissiveTexture = readTexture(ctx, g.emissiveTexture, where + " emissiveTexture");
  m.normalTexture = readTexture(ctx, g.normalTexture, where + " normalTexture");
  if (!std::isfinite(float(g.normalTexture.scale)))
    ctx.fail(where + " normalTexture scale is not finite");
  m.normalTexture.scale = float(g.normalTexture.scale);

  const auto& ext = g.extensions;
  if (const auto* e = findExtension(ext, "KHR_materials_emissive_strength")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_emissive_strength");
    m.emissive *= float(r.number("emissiveStrength", 1.0, 0.0));
  }
  if (const auto* e = findExtension(ext, "KHR_materials_transmission")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_transmission");
    m.transmission = float(r.number("transmissionFactor", 0.0, 0.0, 1.0));
  }
  if (const auto* e = findExtension(ext, "KHR_materials_ior")) {
    ExtensionReader r(ctx, *e, where + " KHR_materials_ior");
    m.ior = float(r.number("ior", 1.5, 1.0));
  }
  readMaterialLayers(ctx, g, where, m);
  // KHR_materials_unlit has no properties: its presence is the whole statement.
  if (findExtension(ext, "KHR_materials_unlit")) m.unlit = true;
  if (const auto* e = findExtension(ext, "TRAY_materials_priority")) {
    ExtensionReader r(ctx, *e, where + " TRAY_materials_priority");
    m.priority = r.integer("priority", 0);
    r.finish();
  }
  if (const auto* e = findExtension(ext, "TRAY_materials_hair"))
    readHairMaterial(ctx, *e, where, m);  // Chiang et al. 2016 (docs/curves-subdivision.md)
  // The Phong mapping reads the PBR factors above, so it comes last.
  if (const auto* e = findExtension(ext, "TRAY_materials_phong")) {
    m.phong = readPhong(ctx, *e, where);
    m.hasPhong = true;
  } else {
    m.phong = phongFromPbr(m);
  }
  return m;
}

}  // namespace tray

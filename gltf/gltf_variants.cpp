#include "gltf/gltf_variants.h"

#include "gltf/gltf_value.h"

namespace tray {

namespace {

constexpr const char* kVariants = "KHR_materials_variants";

/// An index held in a tinygltf::Value (a JSON integer, or a real with an integral value), or -1.
int indexOf(const tinygltf::Value& v) {
  if (v.IsInt()) return v.Get<int>();
  if (v.IsReal()) {
    const double d = v.Get<double>();
    if (d >= 0 && d < 2147483647.0 && d == double(int(d))) return int(d);
  }
  return -1;
}

}  // namespace

std::vector<std::string> readVariantNames(const GltfContext& ctx) {
  std::vector<std::string> names;
  const tinygltf::Value* root = findExtension(ctx.model.extensions, kVariants);
  if (!root) return names;
  const std::string where = std::string(kVariants) + " (root)";
  if (!root->IsObject() || !root->Has("variants") || !root->Get("variants").IsArray())
    ctx.fail(where + ": 'variants' must be an array");
  const tinygltf::Value& list = root->Get("variants");
  for (size_t i = 0; i < list.ArrayLen(); ++i) {
    const tinygltf::Value& v = list.Get(int(i));
    if (!v.IsObject() || (v.Has("name") && !v.Get("name").IsString()))
      ctx.fail(where + ": variant " + std::to_string(i) + " must be an object with a string name");
    names.push_back(v.Has("name") ? v.Get("name").Get<std::string>() : std::string());
  }
  return names;
}

void validateVariantMappings(const GltfContext& ctx, size_t variantCount) {
  const auto& m = ctx.model;
  for (size_t mesh = 0; mesh < m.meshes.size(); ++mesh)
    for (size_t i = 0; i < m.meshes[mesh].primitives.size(); ++i) {
      const tinygltf::Value* ext =
          findExtension(m.meshes[mesh].primitives[i].extensions, kVariants);
      if (!ext) continue;
      const std::string where = nameOf("mesh", int(mesh), m.meshes[mesh].name) + " primitive " +
                                std::to_string(i) + " " + kVariants;
      if (!ext->IsObject() || !ext->Has("mappings") || !ext->Get("mappings").IsArray())
        ctx.fail(where + ": 'mappings' must be an array");
      const tinygltf::Value& mappings = ext->Get("mappings");
      for (size_t k = 0; k < mappings.ArrayLen(); ++k) {
        const tinygltf::Value& map = mappings.Get(int(k));
        const std::string at = where + " mapping " + std::to_string(k);
        if (!map.IsObject() || !map.Has("material") || !map.Has("variants") ||
            !map.Get("variants").IsArray())
          ctx.fail(at + ": needs 'material' and an array 'variants'");
        const int material = indexOf(map.Get("material"));
        if (material < 0 || size_t(material) >= m.materials.size())
          ctx.fail(at + ": material is not an index of the file's " +
                   std::to_string(m.materials.size()) + " material(s)");
        const tinygltf::Value& vs = map.Get("variants");
        for (size_t j = 0; j < vs.ArrayLen(); ++j) {
          const int v = indexOf(vs.Get(int(j)));
          if (v < 0 || size_t(v) >= variantCount)
            ctx.fail(at + ": variant is not an index of the root's " +
                     std::to_string(variantCount) + " variant(s)");
        }
      }
    }
}

int chooseVariant(const GltfContext& ctx, const std::vector<std::string>& names,
                  const std::string& which) {
  if (which == "none") return -1;
  if (const int i = findByNameOrIndex(names, which); i >= 0) return i;
  ctx.fail("--variant " + which + ": no such material variant (the file has " +
           std::to_string(names.size()) + listOfChoices(names) + "; or none)");
}

int variantMaterial(const tinygltf::Primitive& p, int variant) {
  if (variant < 0) return p.material;
  const tinygltf::Value* ext = findExtension(p.extensions, kVariants);
  if (!ext) return p.material;
  const tinygltf::Value& mappings = ext->Get("mappings");  // checked by validateVariantMappings
  for (size_t k = 0; k < mappings.ArrayLen(); ++k) {
    const tinygltf::Value& vs = mappings.Get(int(k)).Get("variants");
    for (size_t j = 0; j < vs.ArrayLen(); ++j)
      if (indexOf(vs.Get(int(j))) == variant) return indexOf(mappings.Get(int(k)).Get("material"));
  }
  return p.material;
}

}  // namespace tray

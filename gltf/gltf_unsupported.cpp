#include "gltf/gltf_unsupported.h"

#include <map>

#include "gltf/gltf_value.h"

namespace tray {

namespace {

/// Attribute semantics read by gltf/gltf_meshes.cpp; any other is ignored (application-specific
/// ones, "_NAME", are not glTF features and pass without a word).
bool isRead(const std::string& semantic) {
  return semantic == "POSITION" || semantic == "NORMAL" || semantic == "TANGENT" ||
         semantic == "TEXCOORD_0" || semantic == "TEXCOORD_1" || semantic == "COLOR_0" ||
         semantic == "JOINTS_0" || semantic == "JOINTS_1" || semantic == "WEIGHTS_0" ||
         semantic == "WEIGHTS_1";
}

std::string count(size_t n, const char* what) {
  return std::to_string(n) + " " + what;
}

}  // namespace

void warnUnsupported(const GltfContext& ctx) {
  const auto& m = ctx.model;
  // Animations, skins and morph targets are read (gltf/gltf_animation.h, gltf/gltf_deform.h).
  std::map<std::string, size_t> ignored;  // attribute semantic -> primitives
  for (const auto& mesh : m.meshes)
    for (const auto& p : mesh.primitives) {
      for (const auto& [semantic, accessor] : p.attributes)
        if (!isRead(semantic) && semantic.rfind('_', 0) != 0) ++ignored[semantic];
    }
  if (!ignored.empty()) {
    std::string list;
    for (const auto& [semantic, n] : ignored) list += (list.empty() ? "" : ", ") + semantic;
    ctx.warn("vertex attribute(s) " + list + " ignored (TRay reads POSITION, NORMAL, TANGENT, " +
             "TEXCOORD_0/1, COLOR_0, JOINTS_0/1 and WEIGHTS_0/1)");
  }
  size_t occlusion = 0, highUv = 0;
  for (const auto& g : m.materials) {
    if (g.occlusionTexture.index >= 0) ++occlusion;
    for (int texCoord : {g.pbrMetallicRoughness.baseColorTexture.texCoord,
                         g.pbrMetallicRoughness.metallicRoughnessTexture.texCoord,
                         g.emissiveTexture.texCoord, g.normalTexture.texCoord})
      if (texCoord > 1) ++highUv;
  }
  if (occlusion)
    ctx.warn(count(occlusion,
                   "material(s) with an occlusionTexture: ignored (occlusion is "
                   "traced)"));
  if (highUv)
    ctx.warn(count(highUv, "texture reference(s) to TEXCOORD_2 or above: TEXCOORD_0 is used"));
}

}  // namespace tray

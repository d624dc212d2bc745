#include "gltf/gltf_validate.h"

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "gltf/gltf_accessors.h"

namespace tray {

namespace {

bool inRange(int index, size_t size) {
  return index >= 0 && size_t(index) < size;
}

/// Why TRay leaves out an extension that real assets use (issue 39: a refusal names its
/// reason), or "" for one it does not know at all.
std::string unsupportedReason(const std::string& name) {
  static const std::map<std::string, std::string> kReasons = {
      {"KHR_materials_pbrSpecularGlossiness",
       "archived by Khronos in favour of KHR_materials_specular and KHR_materials_ior; convert "
       "the file with `gltf-transform metalrough`"},
      {"KHR_draco_mesh_compression",
       "TRay decodes no Draco-compressed geometry; use the asset's uncompressed variant"},
      {"EXT_meshopt_compression",
       "TRay decodes no meshoptimizer-compressed buffers; use the asset's uncompressed variant"},
      {"KHR_texture_basisu",
       "TRay decodes no KTX2/Basis Universal textures; use the asset's PNG/JPEG variant"},
  };
  const auto it = kReasons.find(name);
  return it == kReasons.end() ? std::string() : it->second;
}

void checkExtensions(const GltfContext& ctx) {
  std::set<std::string> warned;
  for (const auto& e : ctx.model.extensionsRequired) {
    if (isKnownExtension(e)) continue;
    std::string line = "required extension '" + e + "' is not supported";
    if (const std::string why = unsupportedReason(e); !why.empty()) line += ": " + why;
    if (!ctx.ignoreRequiredExtensions) ctx.fail(line);
    if (warned.insert(e).second)
      ctx.warn("required extension '" + e + "' is not supported: rendering without it " +
               "(--ignore-required-extensions); the image may be wrong");
  }
  for (const auto& e : ctx.model.extensionsUsed)
    if (!isKnownExtension(e) && warned.insert(e).second) {
      std::string line = "extension '" + e + "' is not supported and is ignored";
      if (const std::string why = unsupportedReason(e); !why.empty()) line += " (" + why + ")";
      ctx.warn(line);
    }
}

void checkTextures(const GltfContext& ctx) {
  const auto& m = ctx.model;
  for (size_t i = 0; i < m.textures.size(); ++i) {
    const auto& t = m.textures[i];
    if (t.source != -1 && !inRange(t.source, m.images.size()))
      ctx.fail(nameOf("texture", int(i)) + " refers to missing image " + std::to_string(t.source));
    if (t.sampler != -1 && !inRange(t.sampler, m.samplers.size()))
      ctx.fail(nameOf("texture", int(i)) + " refers to missing sampler " +
               std::to_string(t.sampler));
  }
  for (size_t i = 0; i < m.images.size(); ++i)
    if (m.images[i].bufferView != -1 && !inRange(m.images[i].bufferView, m.bufferViews.size()))
      ctx.fail(nameOf("image", int(i)) + " refers to missing bufferView " +
               std::to_string(m.images[i].bufferView));
}

bool isFloat(int t) {
  return t == TINYGLTF_COMPONENT_TYPE_FLOAT;
}
bool isUnsignedNormalized(const tinygltf::Accessor& a) {
  return a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                          a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}
bool isQuantizable(int t) {  // KHR_mesh_quantization adds 8- and 16-bit integers
  return t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         t == TINYGLTF_COMPONENT_TYPE_SHORT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
}

/// The accessor types glTF 2.0 §3.7.2.1 ("Meshes / Overview", attribute table) allows for a
/// semantic, widened by KHR_mesh_quantization when the file uses it. "" if allowed.
std::string attributeProblem(const std::string& semantic, const tinygltf::Accessor& a,
                             bool quantized) {
  const int c = a.componentType, t = a.type;
  auto startsWith = [&](const char* p) { return semantic.rfind(p, 0) == 0; };
  bool ok = true;
  if (semantic == "POSITION") {
    ok = t == TINYGLTF_TYPE_VEC3 && (isFloat(c) || (quantized && isQuantizable(c)));
  } else if (semantic == "NORMAL" || semantic == "TANGENT") {
    bool signedNorm =
        a.normalized && (c == TINYGLTF_COMPONENT_TYPE_BYTE || c == TINYGLTF_COMPONENT_TYPE_SHORT);
    ok = t == (semantic == "NORMAL" ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4) &&
         (isFloat(c) || (quantized && signedNorm));
  } else if (startsWith("TEXCOORD_")) {
    ok = t == TINYGLTF_TYPE_VEC2 &&
         (isFloat(c) || isUnsignedNormalized(a) || (quantized && isQuantizable(c)));
  } else if (startsWith("COLOR_")) {
    ok = (t == TINYGLTF_TYPE_VEC3 || t == TINYGLTF_TYPE_VEC4) &&
         (isFloat(c) || isUnsignedNormalized(a));
  } else if (startsWith("JOINTS_")) {
    ok =
        t == TINYGLTF_TYPE_VEC4 && !a.normalized &&
        (c == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || c == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  } else if (startsWith("WEIGHTS_")) {
    ok = t == TINYGLTF_TYPE_VEC4 && (isFloat(c) || isUnsignedNormalized(a));
  }
  return ok ? "" : "has a component type or element type not allowed for " + semantic;
}

void checkPrimitive(const GltfContext& ctx, const std::string& where, const tinygltf::Primitive& p,
                    bool quantized) {
  const auto& m = ctx.model;
  if (p.mode < -1 || p.mode > TINYGLTF_MODE_TRIANGLE_FAN)
    ctx.fail(where + " has invalid mode " + std::to_string(p.mode));
  if (p.material != -1 && !inRange(p.material, m.materials.size()))
    ctx.fail(where + " refers to missing material " + std::to_string(p.material));
  if (p.attributes.empty()) ctx.fail(where + " has no attributes");
  int64_t count = -1;
  for (const auto& [semantic, index] : p.attributes) {
    if (!inRange(index, m.accessors.size()))
      ctx.fail(where + " attribute " + semantic + " refers to missing accessor " +
               std::to_string(index));
    const auto& a = m.accessors[size_t(index)];
    std::string problem = attributeProblem(semantic, a, quantized);
    if (!problem.empty()) ctx.fail(nameOf("accessor", index) + " (" + semantic + ") " + problem);
    if (count >= 0 && int64_t(a.count) != count)
      ctx.fail(where + " attributes have different counts (" + semantic + " has " +
               std::to_string(a.count) + ", others " + std::to_string(count) + ")");
    count = int64_t(a.count);
  }
  if (p.indices != -1) {
    if (!inRange(p.indices, m.accessors.size()))
      ctx.fail(where + " refers to missing index accessor " + std::to_string(p.indices));
    const auto& a = m.accessors[size_t(p.indices)];
    int c = a.componentType;
    if (a.type != TINYGLTF_TYPE_SCALAR || a.normalized ||
        (c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
      ctx.fail(nameOf("accessor", p.indices) +
               " (indices) must be SCALAR unsigned byte, short or int");
  }
  // Morph target accessors are checked where they are applied (gltf/gltf_deform.cpp).
  for (const auto& target : p.targets)
    for (const auto& [semantic, index] : target)
      if (!inRange(index, m.accessors.size()))
        ctx.fail(where + " morph target " + semantic + " refers to missing accessor " +
                 std::to_string(index));
}

void checkMeshes(const GltfContext& ctx) {
  const auto& used = ctx.model.extensionsUsed;
  bool quantized = std::find(used.begin(), used.end(), "KHR_mesh_quantization") != used.end();
  for (size_t i = 0; i < ctx.model.meshes.size(); ++i) {
    const auto& mesh = ctx.model.meshes[i];
    if (mesh.primitives.empty()) ctx.fail(nameOf("mesh", int(i), mesh.name) + " has no primitives");
    for (size_t j = 0; j < mesh.primitives.size(); ++j)
      checkPrimitive(ctx, nameOf("mesh", int(i), mesh.name) + " primitive " + std::to_string(j),
                     mesh.primitives[j], quantized);
  }
}

/// glTF 2.0 §3.5.3 ("Nodes and Hierarchy"): the node graph is a forest. One parent each, no
/// cycles; checked without recursion so a deep or cyclic file cannot overflow the stack.
void checkNodeGraph(const GltfContext& ctx, std::vector<int>& parent) {
  const auto& nodes = ctx.model.nodes;
  parent.assign(nodes.size(), -1);
  for (size_t i = 0; i < nodes.size(); ++i) {
    const auto& n = nodes[i];
    const std::string name = nameOf("node", int(i), n.name);
    for (int c : n.children) {
      if (!inRange(c, nodes.size())) ctx.fail(name + " has missing child " + std::to_string(c));
      if (parent[size_t(c)] != -1)
        ctx.fail(nameOf("node", c) + " has two parents (nodes " +
                 std::to_string(parent[size_t(c)]) + " and " + std::to_string(i) + ")");
      parent[size_t(c)] = int(i);
    }
    if (n.mesh != -1 && !inRange(n.mesh, ctx.model.meshes.size()))
      ctx.fail(name + " refers to missing mesh " + std::to_string(n.mesh));
    if (n.camera != -1 && !inRange(n.camera, ctx.model.cameras.size()))
      ctx.fail(name + " refers to missing camera " + std::to_string(n.camera));
    if (n.skin != -1 && !inRange(n.skin, ctx.model.skins.size()))
      ctx.fail(name + " refers to missing skin " + std::to_string(n.skin));
  }
  // With one parent each, a cycle is a parent chain that comes back to where it started.
  enum : char { kUnseen, kOnChain, kDone };
  std::vector<char> state(nodes.size(), kUnseen);
  std::vector<int> chain;
  for (size_t start = 0; start < nodes.size(); ++start) {
    chain.clear();
    int n = int(start);
    while (n != -1 && state[size_t(n)] == kUnseen) {
      state[size_t(n)] = kOnChain;
      chain.push_back(n);
      n = parent[size_t(n)];
    }
    if (n != -1 && state[size_t(n)] == kOnChain)
      ctx.fail(nameOf("node", n, nodes[size_t(n)].name) + " is its own ancestor (cycle)");
    for (int c : chain) state[size_t(c)] = kDone;
  }
}

void checkScenes(const GltfContext& ctx, const std::vector<int>& parent) {
  const auto& m = ctx.model;
  if (m.defaultScene != -1 && !inRange(m.defaultScene, m.scenes.size()))
    ctx.fail("default scene " + std::to_string(m.defaultScene) + " does not exist");
  for (size_t i = 0; i < m.scenes.size(); ++i) {
    const std::string name = nameOf("scene", int(i), m.scenes[i].name);
    std::set<int> seen;
    for (int n : m.scenes[i].nodes) {
      if (!inRange(n, m.nodes.size()))
        ctx.fail(name + " refers to missing node " + std::to_string(n));
      if (parent[size_t(n)] != -1)
        ctx.fail(name + " lists node " + std::to_string(n) + " which is not a root");
      if (!seen.insert(n).second) ctx.fail(name + " lists node " + std::to_string(n) + " twice");
    }
  }
}

}  // namespace

bool isKnownExtension(const std::string& name) {
  static const std::set<std::string> kKnown = {"KHR_lights_punctual",
                                               "KHR_materials_emissive_strength",
                                               "KHR_materials_transmission",
                                               "KHR_materials_ior",
                                               "KHR_materials_unlit",
                                               "KHR_texture_transform",
                                               "KHR_materials_volume",
                                               "KHR_materials_specular",
                                               "KHR_materials_clearcoat",
                                               "KHR_materials_sheen",
                                               "KHR_materials_anisotropy",
                                               "KHR_materials_diffuse_transmission",
                                               "KHR_mesh_quantization",
                                               "KHR_materials_variants",
                                               "TRAY_shape",
                                               "TRAY_materials_phong",
                                               "TRAY_materials_priority",
                                               "TRAY_environment",
                                               "TRAY_camera",
                                               "KHR_materials_iridescence",
                                               "KHR_materials_dispersion",
                                               "EXT_mesh_gpu_instancing",
                                               "TRAY_materials_scattering",
                                               "TRAY_materials_hair"};
  return kKnown.count(name) != 0;
}

void validateDocument(const GltfContext& ctx) {
  checkExtensions(ctx);
  checkBufferViews(ctx);
  checkAccessors(ctx);
  warnAccessorBounds(ctx);
  checkTextures(ctx);
  checkMeshes(ctx);
  std::vector<int> parent;
  checkNodeGraph(ctx, parent);
  checkScenes(ctx, parent);
}

}  // namespace tray

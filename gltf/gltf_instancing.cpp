#include "gltf/gltf_instancing.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "gltf/gltf_accessors.h"
#include "gltf/gltf_value.h"

namespace tray {

namespace {

bool isSignedInt(int c) {
  return c == TINYGLTF_COMPONENT_TYPE_BYTE || c == TINYGLTF_COMPONENT_TYPE_SHORT;
}

/// Whether EXT_mesh_gpu_instancing allows accessor `a` for attribute `semantic`. The extension's
/// table: TRANSLATION and SCALE are float VEC3, ROTATION a VEC4 of floats or signed normalized
/// bytes or shorts; with KHR_mesh_quantization TRANSLATION and SCALE may also be signed bytes or
/// shorts, normalized or not (the extension's "KHR_mesh_quantization" section).
bool allowed(const std::string& semantic, const tinygltf::Accessor& a, bool quantized) {
  const int c = a.componentType;
  const bool isFloat = c == TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized;
  if (semantic == "ROTATION")
    return a.type == TINYGLTF_TYPE_VEC4 && (isFloat || (a.normalized && isSignedInt(c)));
  return a.type == TINYGLTF_TYPE_VEC3 && (isFloat || (quantized && isSignedInt(c)));
}

[[noreturn]] void failInstance(const GltfContext& ctx, const std::string& where, size_t k,
                               const std::string& problem) {
  ctx.fail(where + " EXT_mesh_gpu_instancing instance " + std::to_string(k) + " " + problem);
}

}  // namespace

std::optional<InstanceAttributes> parseInstancing(const GltfContext& ctx, int node) {
  const auto& n = ctx.model.nodes[size_t(node)];
  const tinygltf::Value* ext = findExtension(n.extensions, "EXT_mesh_gpu_instancing");
  if (!ext) return std::nullopt;
  ExtensionReader r(ctx, *ext, nameOf("node", node, n.name) + " EXT_mesh_gpu_instancing");
  const tinygltf::Value* attributes = r.value("attributes");
  if (!attributes || !attributes->IsObject())
    r.fail("needs an 'attributes' object with at least one of TRANSLATION, ROTATION, SCALE");
  const auto& used = ctx.model.extensionsUsed;
  const bool quantized = std::find(used.begin(), used.end(), "KHR_mesh_quantization") != used.end();
  InstanceAttributes out;
  bool counted = false;
  for (const std::string& semantic : attributes->Keys()) {
    int* slot = semantic == "TRANSLATION" ? &out.translation
                : semantic == "ROTATION"  ? &out.rotation
                : semantic == "SCALE"     ? &out.scale
                                          : nullptr;
    // Application-specific attributes ("_ID", "_FEATURE_ID_0") carry no transform.
    if (!slot) {
      if (semantic.rfind('_', 0) != 0)
        ctx.warn(r.where() + " attribute " + semantic + " is unknown and ignored");
      continue;
    }
    const tinygltf::Value& v = attributes->Get(semantic);
    const int index = v.IsNumber() ? int(v.GetNumberAsInt()) : -1;
    if (!v.IsNumber() || index < 0 || size_t(index) >= ctx.model.accessors.size())
      r.fail(semantic + " refers to a missing accessor");
    const auto& a = ctx.model.accessors[size_t(index)];
    if (!allowed(semantic, a, quantized))
      r.fail(semantic + " (" + nameOf("accessor", index, a.name) +
             ") has a component type or element type the extension does not allow (" +
             (semantic == "ROTATION" ? "VEC4 float or normalized byte/short"
                                     : "VEC3 float, or byte/short with KHR_mesh_quantization") +
             ")");
    if (counted && a.count != out.count)
      r.fail("attributes have different counts (" + semantic + " has " + std::to_string(a.count) +
             ", others " + std::to_string(out.count) + ")");
    *slot = index;
    out.count = a.count;
    counted = true;
  }
  if (!counted) r.fail("'attributes' needs at least one of TRANSLATION, ROTATION, SCALE");
  if (out.count > kMaxPrimitives)
    r.fail("places " + std::to_string(out.count) + " instances, more than " +
           std::to_string(kMaxPrimitives));
  return out;
}

InstanceData readInstanceData(const GltfContext& ctx, const InstanceAttributes& a) {
  InstanceData d;
  if (a.translation >= 0) d.t = readFloats(ctx, a.translation);
  if (a.rotation >= 0) d.r = readFloats(ctx, a.rotation);
  if (a.scale >= 0) d.s = readFloats(ctx, a.scale);
  return d;
}

namespace {

/// Instance k's attribute `name` (size floats at v) must be finite.
void checkFinite(const GltfContext& ctx, const float* v, int size, const char* name,
                 const std::string& where, size_t k) {
  for (int i = 0; i < size; ++i)
    if (!std::isfinite(v[i])) failInstance(ctx, where, k, std::string(name) + " is not finite");
}

/// Instance k's ROTATION as a matrix. Quantized rotations are unit only to the quantization
/// step: renormalised in double, as node rotations are (gltf/gltf_scene_graph.cpp).
Mat4 instanceRotation(const GltfContext& ctx, const float* r, const std::string& where, size_t k) {
  const double len = std::sqrt(double(r[0]) * r[0] + double(r[1]) * r[1] + double(r[2]) * r[2] +
                               double(r[3]) * r[3]);
  if (!(len > 0)) failInstance(ctx, where, k, "ROTATION is not a unit quaternion");
  return Mat4::rotate(float(r[0] / len), float(r[1] / len), float(r[2] / len), float(r[3] / len));
}

}  // namespace

Mat4 instanceMatrix(const GltfContext& ctx, const float* t, const float* r, const float* s,
                    const std::string& where, size_t k) {
  if (t) checkFinite(ctx, t, 3, "TRANSLATION", where, k);
  if (r) checkFinite(ctx, r, 4, "ROTATION", where, k);
  if (s) checkFinite(ctx, s, 3, "SCALE", where, k);
  Mat4 tm, rm, sm;
  if (t) tm = Mat4::translate({t[0], t[1], t[2]});
  if (r) rm = instanceRotation(ctx, r, where, k);
  if (s) sm = Mat4::scale({s[0], s[1], s[2]});
  return tm * rm * sm;
}

void composeInstanceMatrices(const GltfContext& ctx, const InstanceAttributes& a,
                             const std::string& where, std::vector<Affine3>& out) {
  out.assign(a.count, affineOf(Mat4()));
  // S, then R * S, then T * R * S: each attribute read, applied to every instance and freed.
  if (a.scale >= 0) {
    const std::vector<float> s = readFloats(ctx, a.scale);
    for (size_t k = 0; k < a.count; ++k) {
      const float* v = &s[3 * k];
      checkFinite(ctx, v, 3, "SCALE", where, k);
      out[k] = affineOf(Mat4::scale({v[0], v[1], v[2]}));
    }
  }
  if (a.rotation >= 0) {
    const std::vector<float> r = readFloats(ctx, a.rotation);
    for (size_t k = 0; k < a.count; ++k) {
      const float* q = &r[4 * k];
      checkFinite(ctx, q, 4, "ROTATION", where, k);
      out[k] = affineOf(instanceRotation(ctx, q, where, k) * mat4Of(out[k]));
    }
  }
  if (a.translation >= 0) {
    const std::vector<float> t = readFloats(ctx, a.translation);
    for (size_t k = 0; k < a.count; ++k) {
      const float* v = &t[3 * k];
      checkFinite(ctx, v, 3, "TRANSLATION", where, k);
      out[k] = affineOf(Mat4::translate({v[0], v[1], v[2]}) * mat4Of(out[k]));
    }
  }
}

}  // namespace tray

#pragma once
// EXT_mesh_gpu_instancing (glTF vendor extension): a node that places its mesh many times, each
// instance with its own translation, rotation and scale read from accessors. TRay places one
// Primitive per instance over the mesh stored once (an Embree instance / a top-level BVH leaf
// each), or from 1024 instances one instance array for them all (core/instance_array.h): an
// instance costs a transform, not a copy of the geometry (docs/instancing.md).
#include <cstddef>
#include <optional>
#include <string>

#include "core/instance_array.h"
#include "core/transform.h"
#include "gltf/gltf_context.h"

namespace tray {

/// The accessors of a node's EXT_mesh_gpu_instancing attributes (-1: absent, the identity
/// part) and the instance count they share.
struct InstanceAttributes {
  int translation = -1, rotation = -1, scale = -1;
  size_t count = 0;
};

/// Node `node`'s instancing, checked (accessor indices, element and component types as the
/// extension allows, widened by KHR_mesh_quantization when the file uses it, equal counts);
/// nullopt without the extension. Throws one line naming the file, node and attribute.
std::optional<InstanceAttributes> parseInstancing(const GltfContext& ctx, int node);

/// Instance k's local matrix T * R * S (the extension's order, as a node's TRS, glTF 2.0
/// §3.5.2) for every k, in order, passed to `place(k, matrix)`. Rotations are renormalised (as
/// node rotations are); a non-finite value or a zero quaternion fails naming the instance.
template <class Place>
void forEachInstance(const GltfContext& ctx, const InstanceAttributes& a, const std::string& where,
                     Place&& place);

/// The matrix of instance k of `where` from its (possibly absent, nullptr) translation,
/// rotation and scale.
Mat4 instanceMatrix(const GltfContext& ctx, const float* t, const float* r, const float* s,
                    const std::string& where, size_t k);

/// Instance arrays (core/instance_array.h): every instance's local matrix T * R * S into `out`
/// (a.count of them), composed one attribute at a time, each read, applied and freed before
/// the next: at most 16 bytes per instance held besides `out`, where forEachInstance holds
/// all three attributes' floats (40). The checks and messages of instanceMatrix.
void composeInstanceMatrices(const GltfContext& ctx, const InstanceAttributes& a,
                             const std::string& where, std::vector<Affine3>& out);

/// Reads the attributes' floats (normalized integers mapped per glTF 2.0 §3.11): one vector
/// per attribute, empty when absent.
struct InstanceData {
  std::vector<float> t, r, s;
};
InstanceData readInstanceData(const GltfContext& ctx, const InstanceAttributes& a);

template <class Place>
void forEachInstance(const GltfContext& ctx, const InstanceAttributes& a, const std::string& where,
                     Place&& place) {
  const InstanceData d = readInstanceData(ctx, a);
  for (size_t k = 0; k < a.count; ++k)
    place(k, instanceMatrix(ctx, d.t.empty() ? nullptr : &d.t[3 * k],
                            d.r.empty() ? nullptr : &d.r[4 * k],
                            d.s.empty() ? nullptr : &d.s[3 * k], where, k));
}

}  // namespace tray

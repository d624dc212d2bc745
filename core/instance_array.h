#pragma once
// Instance arrays (docs/instancing.md, "Instance arrays"): one Primitive for a whole
// EXT_mesh_gpu_instancing set of one static mesh, holding a 3x4 world-to-object matrix per
// instance (48 bytes) instead of a Primitive per instance (216 bytes, a Transform with its
// inverse among them). The object-to-world matrix is derived when a hit is shaded
// (Scene::placement), the only place that reads it; rays, which are many more than shaded hits,
// read the stored world-to-object matrix directly.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/transform.h"

namespace tray {

/// EXT_mesh_gpu_instancing sets of at least this many instances load as instance arrays when
/// they can (gltf/gltf_scene_graph.cpp, asArray; LoadOptions::instanceArrayMin, tray-render
/// --instance-arrays). Measured with bench/instancing_bench
/// (docs/bench/instancing-arrays-2026-12-06.md).
constexpr size_t kInstanceArrayMinInstances = 1024;

/// The top three rows of an affine 4x4 matrix (the fourth is 0 0 0 1), row-major.
struct Affine3 {
  float m[3][4];
};
static_assert(sizeof(Affine3) == 48);

inline Affine3 affineOf(const Mat4& a) {
  Affine3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[i][j];
  return r;
}

inline Mat4 mat4Of(const Affine3& a) {
  Mat4 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[i][j];
  return r;
}

/// A point and a vector moved by a, each row's terms left to right as core/transform_lanes.h's
/// applyAffine.
inline Vec3 affinePoint(const Affine3& a, const Vec3& p) {
  return {a.m[0][0] * p.x + a.m[0][1] * p.y + a.m[0][2] * p.z + a.m[0][3],
          a.m[1][0] * p.x + a.m[1][1] * p.y + a.m[1][2] * p.z + a.m[1][3],
          a.m[2][0] * p.x + a.m[2][1] * p.y + a.m[2][2] * p.z + a.m[2][3]};
}
inline Vec3 affineVector(const Affine3& a, const Vec3& v) {
  return {a.m[0][0] * v.x + a.m[0][1] * v.y + a.m[0][2] * v.z,
          a.m[1][0] * v.x + a.m[1][1] * v.y + a.m[1][2] * v.z,
          a.m[2][0] * v.x + a.m[2][1] * v.y + a.m[2][2] * v.z};
}

/// The placements of one instanced mesh: instance j (0..size()-1) is the node's instance
/// index(j) (the same unless zero-scale instances were skipped), object id firstObjectId +
/// index(j), name "<name>#index(j)".
struct InstanceArray {
  std::vector<Affine3> worldToObject;
  /// Instance j's index in its node; empty when it is j (no instance was skipped).
  std::vector<uint32_t> indexInNode;
  int firstObjectId = 0;
  std::string name;  ///< the node's name, or "node<index>" when it has none

  size_t size() const { return worldToObject.size(); }
  uint32_t index(uint32_t j) const { return indexInNode.empty() ? j : indexInNode[j]; }
  /// Instance j's placement: its stored world-to-object matrix and the object-to-world one
  /// derived from it (in double, core/transform.h's invert). Valid: singular instances are
  /// never stored.
  Transform placement(uint32_t j) const {
    Transform t;
    t.inv = mat4Of(worldToObject[j]);
    invert(t.inv, t.m);
    t.m.m[3][0] = t.m.m[3][1] = t.m.m[3][2] = 0.0f, t.m.m[3][3] = 1.0f;
    return t;
  }
  /// Appends an instance whose world-to-object matrix is `toObject` (invertible), index k in
  /// its node.
  void add(const Mat4& toObject, uint32_t k) {
    if (indexInNode.empty() && k != worldToObject.size()) {  // the first skipped instance
      for (uint32_t j = 0; j < worldToObject.size(); ++j) indexInNode.push_back(j);
      indexInNode.push_back(k);
    } else if (!indexInNode.empty()) {
      indexInNode.push_back(k);
    }
    worldToObject.push_back(affineOf(toObject));
  }
};

}  // namespace tray

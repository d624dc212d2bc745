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
  /// derived from it (affineInverse). Singular instances are never stored.
  Transform placement(uint32_t j) const {
    Transform t;
    t.inv = mat4Of(worldToObject[j]);
    t.m = affineInverse(worldToObject[j]);
    return t;
  }
  /// The inverse of an invertible affine a, in double: the 3x3 part by cofactors over the
  /// determinant, the translation -A^-1 t. Per shaded hit, cheaper than core/transform.h's
  /// 4x4 Gauss-Jordan elimination.
  static Mat4 affineInverse(const Affine3& a) {
    double m[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) m[r][c] = a.m[r][c];
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double invDet = 1.0 / (m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02);
    const double inv[3][3] = {{c00 * invDet, (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * invDet,
                               (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * invDet},
                              {c01 * invDet, (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * invDet,
                               (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * invDet},
                              {c02 * invDet, (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * invDet,
                               (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * invDet}};
    Mat4 r;
    for (int i = 0; i < 3; ++i) {
      for (int c = 0; c < 3; ++c) r.m[i][c] = float(inv[i][c]);
      r.m[i][3] = float(-(inv[i][0] * a.m[0][3] + inv[i][1] * a.m[1][3] + inv[i][2] * a.m[2][3]));
    }
    return r;
  }
};

}  // namespace tray

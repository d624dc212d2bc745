#pragma once
// The bottom level: one tree per TriangleMesh, built once and shared by every instance of it.
// Rays arrive in the mesh's object space (direction not normalised, so t is the world t), as
// with Embree's instances.
#include <cstdint>
#include <vector>

#include "accel/bvh.h"
#include "core/hit.h"
#include "core/ray.h"
#include "shapes/triangle_mesh.h"

namespace tray {

/// Triangle vertices copied in leaf order, so a leaf's triangles are contiguous in memory.
struct BvhTriangle {
  Vec3 p0, p1, p2;
  uint32_t index;  ///< triangle index within the mesh
};

class MeshBvh {
 public:
  /// hierarchy = false: no tree, every query tests every triangle (the naive accelerator).
  MeshBvh(const TriangleMesh& mesh, const BvhBuildOptions& options, bool hierarchy = true);

  /// Closest triangle with t in (ray.tmin, tmax); lowers tmax and fills hit's mesh fields.
  bool intersect(const Ray& ray, float& tmax, Hit& hit) const;
  /// Any triangle with t in (ray.tmin, ray.tmax); its index goes to `triangle`.
  bool occluded(const Ray& ray, uint32_t& triangle) const;
  /// Appends every triangle hit in (ray.tmin, ray.tmax), tagged with `primitive`.
  void allHits(const Ray& ray, uint32_t primitive, std::vector<Hit>& hits) const;
  /// Tests one triangle by its mesh index (the last-occluder cache).
  bool occludedBy(const Ray& ray, uint32_t triangle) const;

  Bounds3 bounds() const { return bounds_; }
  const Bvh& tree() const { return bvh_; }
  size_t memoryBytes() const {
    return bvh_.memoryBytes() + triangles_.capacity() * sizeof(BvhTriangle);
  }

 private:
  template <class OnHit>
  bool forEachCandidate(const Ray& ray, const float& tmax, OnHit&& onHit) const;

  Bvh bvh_;
  const TriangleMesh& mesh_;
  std::vector<BvhTriangle> triangles_;  ///< in leaf order (bvh_.primitives), or mesh order
  Bounds3 bounds_;
  bool hierarchy_;
};

}  // namespace tray

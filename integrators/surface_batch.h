#pragma once
// A wave's surface points in SIMD (Highway, dynamic dispatch): Scene::surface for the hits on
// static triangle meshes, many at once, bit for bit the scalar code's (docs/wavefront.md,
// "Surfaces in SIMD"). The wavefront's first shading stage over its queue.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/hit.h"
#include "core/ray.h"
#include "core/scene.h"

namespace tray {

/// What the kernel reads of one primitive (plain values, gathered once by SurfaceBatch).
struct SurfaceBatchPrimitive {
  bool hasNormals = false, hasUvs = false;
  int32_t material = 0;
  const Transform* toWorld =
      nullptr;  ///< the Primitive's: a copy would cost 128 bytes per instance
  const uint32_t* indices = nullptr;
  const float* positions = nullptr;  ///< Vec3s as floats
  const float* normals = nullptr;
  const float* uvs = nullptr;  ///< Vec2s as floats
};

/// Scene::surface over a wave's queue. Hits are grouped by primitive (a counting sort), so that
/// a group's transform and arrays are the same for every lane and only vertices are gathered.
class SurfaceBatch {
 public:
  /// A thread's working memory, reused from one call to the next (no allocation once grown).
  struct Scratch {
    std::vector<uint32_t> count;  ///< per primitive; zero between calls
    std::vector<uint32_t> seen;   ///< the primitives of this call, in order of first hit
    std::vector<uint32_t> begin;  ///< per primitive, its group's start in `order`
    std::vector<int32_t> order;   ///< hit indices grouped by primitive
    std::vector<uint32_t> group;  ///< per hit, its primitive when batched, else kNoPrimitive
  };
  explicit SurfaceBatch(const Scene& scene);
  /// False when the CPU has no SIMD target or no primitive is a static triangle mesh: the
  /// caller then calls Scene::surface itself.
  bool useful() const { return useful_; }
  /// out[j] = scene.surface(rays[j], hits[j]) for every j with found[j] (others left as they
  /// are).
  void compute(std::span<const Ray> rays, std::span<const Hit> hits, std::span<const uint8_t> found,
               std::span<SurfacePoint> out, Scratch& scratch) const;

 private:
  const Scene& scene_;
  std::vector<SurfaceBatchPrimitive> primitives_;
  /// Per primitive: a static triangle mesh, the kernel's (else Scene::surface's); apart from
  /// primitives_ so that the per-hit test reads a byte, not the struct.
  std::vector<uint8_t> batched_;
  bool useful_ = false;
};

}  // namespace tray

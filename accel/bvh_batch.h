#pragma once
// Batched queries of the two-level BVH (Accelerator::intersectBatch / occludedBatch): groups of
// rays of the batch traverse the top tree and each mesh tree together
// (accel/bvh4_packet.h). What packets do not cover, analytic shapes, unbounded shapes and
// deforming meshes, each ray of the group queries on its own.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "accel/bvh4.h"
#include "accel/bvh_mesh.h"
#include "core/hit.h"
#include "core/ray.h"
#include "core/scene.h"

namespace tray {

/// What the batched queries read of a two-level accelerator (accel/bvh_accelerator.cpp), and
/// its single-ray query of one placed primitive, for primitives that packets do not cover.
class TwoLevelParts {
 public:
  virtual ~TwoLevelParts() = default;
  /// As the single-ray closest-hit query does for primitive i: lowers tmax and sets hit.
  virtual bool intersectPrimitive(uint32_t i, const Ray& ray, float& tmax, Hit& hit) const = 0;
  /// As the single-ray any-hit query does for primitive i, remembering a blocker in the
  /// last-occluder cache.
  virtual bool occludedPrimitive(uint32_t i, const Ray& ray) const = 0;
  /// The last-occluder cache of the single-ray query (accel/bvh_accelerator.cpp): true if the
  /// primitive and block that blocked this thread's last shadow ray block `ray`.
  virtual bool occludedByCached(const Ray& ray) const = 0;
  virtual void cacheOccluder(uint32_t primitive, uint32_t block) const = 0;

  const Scene* scene = nullptr;
  const Bvh4* top = nullptr;
  const std::vector<std::unique_ptr<MeshBvh>>* meshes = nullptr;  ///< by mesh index
  const std::vector<char>* alphaTested = nullptr;                 ///< by mesh index
  const std::vector<uint32_t>* unbounded = nullptr;  ///< primitives every ray tests
  uint32_t single = kNoPrimitive;  ///< the only primitive of the top tree, which is skipped
};

/// found[i] = intersect(rays[i], hits[i]) for each ray, traced `group` rays (at most
/// kMaxPacketRays) at a time: consecutive rays of the batch, or with `byOctant` consecutive
/// rays of those whose directions share an octant.
void twoLevelIntersectBatch(const TwoLevelParts& parts, int group, bool byOctant,
                            std::span<const Ray> rays, std::span<Hit> hits,
                            std::span<uint8_t> found);
/// blocked[i] = occluded(rays[i]) for each ray, grouped as twoLevelIntersectBatch does.
void twoLevelOccludedBatch(const TwoLevelParts& parts, int group, bool byOctant,
                           std::span<const Ray> rays, std::span<uint8_t> blocked);

}  // namespace tray

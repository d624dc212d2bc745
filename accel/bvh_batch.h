#pragma once
// Batched queries of the two-level BVH (Accelerator::intersectBatch / occludedBatch): groups of
// rays of the batch traverse the top tree and each mesh tree together
// (accel/bvh4_packet.h). What packets do not cover, analytic shapes, unbounded shapes and
// deforming meshes, each ray of the group queries on its own.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "accel/bvh4.h"
#include "accel/bvh_instance_boxes.h"
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
  /// As the single-ray closest-hit query does for item i (a primitive or an instance of an
  /// instance array, see placed()): lowers tmax and sets hit.
  virtual bool intersectPrimitive(uint32_t i, const Ray& ray, float& tmax, Hit& hit) const = 0;
  /// As the single-ray any-hit query does for primitive i, remembering a blocker in the
  /// last-occluder cache.
  virtual bool occludedPrimitive(uint32_t i, const Ray& ray) const = 0;
  /// The last-occluder cache of the single-ray query (accel/bvh_accelerator.cpp): true if the
  /// primitive and block that blocked this thread's last shadow ray block `ray`.
  virtual bool occludedByCached(const Ray& ray) const = 0;
  /// `member`: which instance of a group (placed(item).instance + member), 0 for a primitive.
  virtual void cacheOccluder(uint32_t item, uint32_t member, uint32_t block) const = 0;

  /// Top-tree leaves are items: items 0..primitives-1 are the primitives (an instance array's
  /// own stays out of the tree), then each instance array's instances in groups of
  /// kArrayGroup consecutive ones, array a's group g at item arrayFirst[a] + g. A group is one
  /// leaf: the top tree over 10^6 instances has an eighth of the nodes to build and hold
  /// (bench/instancing_bench: the binary tree was the peak), and glTF's instances of one set
  /// are laid out in order (rows of a grid, strokes of a scatter tool), so a group's box is
  /// about its instances' own. A ray entering it tests its instances' own boxes
  /// (accel/bvh_instance_boxes.h) and enters only those. Groups of 4 rendered as fast, of 16
  /// slower (docs/bench/instancing-arrays-time-2026-12-07.md).
  static constexpr uint32_t kArrayGroup = 8;
  static constexpr int kGroupBoxNodes = int(kArrayGroup / 4);  ///< InstanceBoxes4 per group
  struct Placed {
    uint32_t primitive, instance, count;  ///< instances instance..instance+count-1 of primitive
    const InstanceBoxes4* boxes;          ///< a group's instances' boxes; null for a primitive
  };
  Placed placed(uint32_t item) const {
    if (item < itemsBase) return {item, 0, 1, nullptr};
    size_t a = arrayFirst.size() - 1;
    while (arrayFirst[a] > item) --a;  // a few arrays at most
    const uint32_t group = item - arrayFirst[a];
    const uint32_t first = group * kArrayGroup;
    return {arrayPrimitive[a], first, std::min(kArrayGroup, arraySize[a] - first),
            &arrayBoxes[a][size_t(group) * kGroupBoxNodes]};
  }
  uint32_t itemsBase = 0;  ///< the number of primitives
  uint32_t itemCount = 0;
  /// Per instance array, ascending: its first item, primitive and instance count.
  std::vector<uint32_t> arrayFirst, arrayPrimitive, arraySize;
  /// Per instance array: its groups' instance boxes, group g's kGroupBoxNodes from
  /// arrayBoxes[a][g * kGroupBoxNodes].
  std::vector<const InstanceBoxes4*> arrayBoxes;

  const Scene* scene = nullptr;
  const Bvh4* top = nullptr;
  const std::vector<std::unique_ptr<MeshBvh>>* meshes = nullptr;  ///< by mesh index
  const std::vector<char>* alphaTested = nullptr;                 ///< by mesh index
  const std::vector<uint32_t>* unbounded = nullptr;               ///< primitives every ray tests
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

#pragma once
// The world boxes of an instance array's instances inside one top-tree leaf of the two-level BVH
// (accel/bvh_batch.h, TwoLevelParts::placed) and inside one Embree user primitive
// (accel/embree_instance_array.h): a leaf holds a group of consecutive instances, so that the
// top tree over 10^6 instances is a fraction of the size to build and hold, and a ray entering
// the group's box tests its instances' own boxes four at once, as a Bvh4Node's four children
// (accel/bvh4_traversal.h, the same slab test), before it is moved into any instance's object
// space. Without them a ray entered every instance of the group: at 10^6 instances in groups of
// 4, 13.1 M ray-instance entries where 2.3 M reached the mesh's root boxes
// (docs/bench/instancing-arrays-time-2026-12-07.md). 96 bytes per four instances: 24 each.
#include <cmath>
#include <cstdint>
#include <vector>

#include "accel/bvh4_traversal.h"
#include "core/bounds.h"
#include "core/instance_array.h"

namespace tray {

struct alignas(16) InstanceBoxes4 {
  float lo[3][4];  ///< [axis][instance of the group]; an empty slot has lo = +inf, hi = -inf
  float hi[3][4];
};
static_assert(sizeof(InstanceBoxes4) == 96);

/// Four empty slots, which no slab test enters.
inline InstanceBoxes4 emptyInstanceBoxes4() {
  InstanceBoxes4 b;
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < 4; ++k) b.lo[a][k] = INFINITY, b.hi[a][k] = -INFINITY;
  return b;
}

inline void setInstanceBox(InstanceBoxes4& b, int k, const Bounds3& box) {
  for (int a = 0; a < 3; ++a) b.lo[a][k] = box.lo[a], b.hi[a][k] = box.hi[a];
}

/// Bit k: the ray enters instance k's box within [tmin, tmax] (the top tree's own box test).
inline int hitInstanceBoxes(const InstanceBoxes4& b, const Bvh4Ray& r, float tmin, float tmax) {
  simd::F4 entry;
  return simd::bits(hitBoxes4Mask(b.lo, b.hi, r, simd::set1(tmin), simd::set1(tmax), entry));
}

/// The same over a group's `nodes` consecutive InstanceBoxes4 (4 instances each): bit k for the
/// group's instance k.
inline unsigned hitGroupBoxes(const InstanceBoxes4* b, int nodes, const Bvh4Ray& r, float tmin,
                              float tmax) {
  unsigned in = 0;
  for (int j = 0; j < nodes; ++j) in |= unsigned(hitInstanceBoxes(b[j], r, tmin, tmax)) << (4 * j);
  return in;
}

/// Requests the world-to-object matrices of instances first..first+count-1 into the cache.
/// Called on entering a group, before its box tests: at 10^6 instances the matrices (48 MB)
/// are mostly out of the cache, and their misses then overlap the boxes' and the tests instead
/// of following them (requested only once a box was entered, or not at all, the 10^6 render
/// took 1-6% (BVH) and 0-9% (Embree) longer: docs/bench/instancing-arrays-time-2026-12-07b.md).
inline void prefetchGroupMatrices(const InstanceArray& array, uint32_t first, uint32_t count) {
  const char* from = reinterpret_cast<const char*>(array.worldToObject.data() + first);
  const char* to = reinterpret_cast<const char*>(array.worldToObject.data() + first + count);
  for (const char* at = from; at < to; at += 64) __builtin_prefetch(at);
  __builtin_prefetch(to - 1);  // the last matrix's end, on a line of its own
}

/// Every instance's world box (the mesh's object-space box placed by it), instance k in slot
/// k % 4 of node k / 4, for groups of `group` instances (a multiple of 4): the nodes of the last
/// group are all there, their unused slots empty. Computed in parallel; an empty mesh box
/// leaves every slot empty.
std::vector<InstanceBoxes4> instanceBoxes(const InstanceArray& array, const Bounds3& meshBounds,
                                          uint32_t group);

/// The box of a group: the union of its `nodes` InstanceBoxes4 (empty slots add nothing).
Bounds3 groupBounds(const InstanceBoxes4* boxes, int nodes);

}  // namespace tray

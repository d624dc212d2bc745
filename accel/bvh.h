#pragma once
// TRay's own bounding volume hierarchy: a flattened binary tree over primitive bounds, built by
// binned SAH (Wald 2007) or by Goldsmith–Salmon incremental insertion (1987). The same tree type
// serves both levels of the two-level accelerator: triangles of one mesh, and the placed
// primitives (instances and analytic shapes) of a scene.
#include <cstdint>
#include <string>
#include <vector>

#include "core/bounds.h"

namespace tray {

/// One node, 32 bytes so two share a cache line. Children of an interior node are stored next to
/// each other at `offset` and `offset + 1` (lets a parallel builder allocate pairs atomically).
/// A leaf holds `count` > 0 primitive references starting at `offset` in Bvh::primitives.
struct BvhNode {
  float lo[3];
  uint32_t offset;
  float hi[3];
  uint16_t count;  ///< 0: interior node
  uint8_t axis;    ///< split axis of an interior node: which child is nearer along the ray
  uint8_t pad;
  bool leaf() const { return count > 0; }
  Bounds3 bounds() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
  void setBounds(const Bounds3& b) {
    for (int i = 0; i < 3; ++i) lo[i] = b.lo[i], hi[i] = b.hi[i];
  }
};
static_assert(sizeof(BvhNode) == 32);

/// A built tree. Node 0 is the root; an empty tree has no nodes.
struct Bvh {
  std::vector<BvhNode> nodes;
  std::vector<uint32_t> primitives;  ///< leaf ranges index into this: input primitive ids
  size_t memoryBytes() const {
    return nodes.capacity() * sizeof(BvhNode) + primitives.capacity() * sizeof(uint32_t);
  }
};

enum class BvhBuilder {
  kBinnedSah,        ///< top-down binned SAH, parallel (TBB)
  kGoldsmithSalmon,  ///< incremental insertion in random order, one primitive per leaf
};

struct BvhBuildOptions {
  BvhBuilder builder = BvhBuilder::kBinnedSah;
  int maxLeafSize = 4;  ///< at most 16 (accel/bvh4.h)
  int bins = 16;
  /// Primitives tested together (accel/bvh_triangle4.h tests four triangles at once): the SAH
  /// counts a leaf's cost in blocks, ceil(count / blockSize), as Embree's builders do, so
  /// leaves fill their blocks. 1: every primitive costs one test (Wald 2007).
  int blockSize = 1;
  /// Binned SAH: from this depth down, splits are object medians, which halve the range, so a
  /// tree stays under sahDepth + 32 levels whatever the input (the traversal stacks assume under
  /// 256: accel/bvh4_traversal.h). At most 200.
  int sahDepth = 200;
  /// SAH constants: cost of one node visit and one primitive test (Wald 2007 uses 1 : 1).
  float traversalCost = 1.0f;
  float intersectionCost = 1.0f;
};

/// Builds a tree over primitives given by their bounds (index = primitive id). Empty or
/// non-finite bounds are left out of the tree.
Bvh buildBvh(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options = {});
Bvh buildBvhBinnedSah(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options);
/// The same tree, `bounds` freed (emptied) once read, before the nodes are made: a top tree
/// over 10^6 instances holds 24 MiB less at its peak.
Bvh buildBvhBinnedSah(std::vector<Bounds3>&& bounds, const BvhBuildOptions& options);
Bvh buildBvhGoldsmithSalmon(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options);

/// Surface area heuristic cost of a tree (MacDonald & Booth 1990): expected cost of a random
/// ray through the root, sum over nodes of area(node)/area(root) times visit or test costs.
double sahCost(const Bvh& bvh, const BvhBuildOptions& options = {});

const char* builderName(BvhBuilder b);

}  // namespace tray

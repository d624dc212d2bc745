#pragma once
// The top level of the two-level BVH (accel/bvh_accelerator.cpp), built once: the tree over the
// scene's items (TwoLevelParts::placed, accel/bvh_batch.h: the placed primitives, then each
// instance array's groups of instances with their instances' boxes), and the primitives that
// sit beside it (unbounded shapes, tested by every ray). The queries read it through
// TwoLevelParts.
#include <cstdint>
#include <memory>
#include <vector>

#include "accel/bvh4.h"
#include "accel/bvh_accelerator.h"
#include "accel/bvh_batch.h"
#include "accel/bvh_instance_boxes.h"
#include "accel/bvh_mesh.h"
#include "core/scene.h"

namespace tray {

struct TopLevel {
  Bvh4 tree;  ///< over the items, one per leaf (empty without a hierarchy)
  std::vector<std::vector<InstanceBoxes4>> arrayBoxes;  ///< per instance array, per group
  uint32_t single = kNoPrimitive;  ///< the only item of `tree`, which the queries then skip
  double sahCost = 0;
  size_t binaryNodes = 0;
  std::vector<uint32_t> unbounded;  ///< shapes with infinite bounds, tested by every ray
  std::vector<uint32_t> flat;       ///< without a hierarchy: every bounded item
};

/// Numbers the scene's items into `parts` (itemsBase, itemCount, arrayFirst, arrayPrimitive,
/// arraySize, arrayBoxes, which then point into the result's arrayBoxes) and builds the top
/// level over them; `meshes` (by mesh index) give a placed mesh its box.
TopLevel buildTopLevel(const Scene& scene, const std::vector<std::unique_ptr<MeshBvh>>& meshes,
                       const TwoLevelOptions& options, TwoLevelParts& parts);

}  // namespace tray

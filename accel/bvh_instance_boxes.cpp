#include "accel/bvh_instance_boxes.h"

#include <tbb/parallel_for.h>

namespace tray {

std::vector<InstanceBoxes4> instanceBoxes(const InstanceArray& array, const Bounds3& meshBounds,
                                          uint32_t group) {
  const size_t n = array.size();
  const size_t groups = (n + group - 1) / group;
  std::vector<InstanceBoxes4> boxes(groups * (group / 4), emptyInstanceBoxes4());
  if (meshBounds.empty()) return boxes;
  tbb::parallel_for(size_t(0), n, [&](size_t k) {
    setInstanceBox(boxes[k / 4], int(k % 4), array.placement(uint32_t(k)).bounds(meshBounds));
  });
  return boxes;
}

Bounds3 groupBounds(const InstanceBoxes4* boxes, int nodes) {
  Bounds3 b;
  for (int j = 0; j < nodes; ++j)
    for (int k = 0; k < 4; ++k)
      if (boxes[j].lo[0][k] <= boxes[j].hi[0][k])  // not an empty slot
        b.extend(Bounds3{{boxes[j].lo[0][k], boxes[j].lo[1][k], boxes[j].lo[2][k]},
                         {boxes[j].hi[0][k], boxes[j].hi[1][k], boxes[j].hi[2][k]}});
  return b;
}

}  // namespace tray

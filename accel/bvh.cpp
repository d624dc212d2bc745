#include "accel/bvh.h"

namespace tray {

Bvh buildBvh(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options) {
  switch (options.builder) {
    case BvhBuilder::kGoldsmithSalmon:
      return buildBvhGoldsmithSalmon(bounds, options);
    case BvhBuilder::kBinnedSah:
      break;
  }
  return buildBvhBinnedSah(bounds, options);
}

double sahCost(const Bvh& bvh, const BvhBuildOptions& options) {
  if (bvh.nodes.empty()) return 0.0;
  double rootArea = bvh.nodes[0].bounds().surfaceArea();
  if (rootArea <= 0) return 0.0;
  double cost = 0;
  for (const BvhNode& n : bvh.nodes) {
    double a = n.bounds().surfaceArea() / rootArea;
    cost += n.leaf() ? a * options.intersectionCost * n.count : a * options.traversalCost;
  }
  return cost;
}

const char* builderName(BvhBuilder b) {
  return b == BvhBuilder::kGoldsmithSalmon ? "goldsmith-salmon" : "binned-sah";
}

}  // namespace tray

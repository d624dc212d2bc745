#pragma once
#include <memory>

#include "accel/bvh.h"
#include "core/accelerator.h"

namespace tray {

struct TwoLevelOptions {
  BvhBuildOptions build;
  /// false: no trees at either level, every query tests every primitive and triangle.
  bool hierarchy = true;
  /// Test the primitive that blocked this thread's last shadow ray first (the seed's cache).
  bool occluderCache = true;
};

/// TRay's own two-level accelerator: a tree over the placed primitives (mesh instances and
/// analytic shapes with finite bounds), and one tree per mesh shared by its instances.
/// Returns the same hits as the Embree accelerator (tests/accel/bvh_accelerator_test.cpp).
std::unique_ptr<Accelerator> makeTwoLevelAccelerator(const Scene& scene,
                                                     const TwoLevelOptions& options);

/// Registry entries: "bvh" (binned SAH), "bvh-gs" (Goldsmith–Salmon), "naive" (no hierarchy).
std::unique_ptr<Accelerator> makeBvhAccelerator(const Scene& scene);
std::unique_ptr<Accelerator> makeBvhGoldsmithSalmonAccelerator(const Scene& scene);
std::unique_ptr<Accelerator> makeNaiveAccelerator(const Scene& scene);

/// SAH cost of the trees of an accelerator made by makeTwoLevelAccelerator: the triangle-count
/// weighted mean over its mesh trees, and the top-level tree's. Zeros for other accelerators.
struct BvhQuality {
  double meshSahCost = 0;
  double topSahCost = 0;
  size_t nodes = 0;      ///< binary nodes, as built
  size_t wideNodes = 0;  ///< 4-wide nodes traversed (accel/bvh4.h)
};
BvhQuality bvhQuality(const Accelerator& accel);

}  // namespace tray

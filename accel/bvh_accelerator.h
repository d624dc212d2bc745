#pragma once
#include <memory>

#include "accel/bvh.h"
#include "core/accelerator.h"

namespace tray {

/// How Accelerator::intersectBatch/occludedBatch trace a batch (bench/path_bench and
/// bench/accel_bench measure them; docs/wavefront.md).
enum class BvhBatch {
  kLoop,      ///< the single-ray query per ray, as the default implementation
  kPacket8,   ///< groups of 8 consecutive rays traverse together (accel/bvh4_packet.h)
  kStream64,  ///< groups of 64 rays whose directions share an octant: small ray streams
};
/// Rays per group of a mode (1 for kLoop).
int bvhBatchRays(BvhBatch batch);

struct TwoLevelOptions {
  BvhBuildOptions build;
  /// false: no trees at either level, every query tests every primitive and triangle.
  bool hierarchy = true;
  /// Test the primitive that blocked this thread's last shadow ray first (the seed's cache).
  bool occluderCache = true;
  /// How batches are traced (the trees need a hierarchy: without one, batches loop). Streams of
  /// 64: the fastest of the three in bench/path_bench and bench/batch_bench (docs/wavefront.md).
  BvhBatch batch = BvhBatch::kStream64;
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

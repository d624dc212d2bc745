#pragma once
#include <memory>

#include "core/accelerator.h"

namespace tray {

/// How Accelerator::intersectBatch/occludedBatch reach Embree (bench/path_bench measures them).
enum class EmbreeBatch {
  kLoop,              ///< rtcIntersect1 per ray, as the default implementation
  kStreamIncoherent,  ///< rtcIntersect1M, the rays flagged incoherent
  kStreamCoherent,    ///< rtcIntersect1M, flagged coherent: Embree gathers them into packets
};

/// Embree 3 traversal: meshes as triangle geometry built once per mesh and placed by instances;
/// analytic shapes as user geometry calling Scene::intersectShape.
std::unique_ptr<Accelerator> makeEmbreeAccelerator(const Scene& scene);
/// Batches use `batch` where the scene has no user geometry (benchmarks compare them).
std::unique_ptr<Accelerator> makeEmbreeAccelerator(const Scene& scene, EmbreeBatch batch);

}  // namespace tray

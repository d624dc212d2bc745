#pragma once
#include <cstddef>

#include "core/integrator.h"

namespace tray {

/// Paths in flight per wave of the wavefront driver: enough to fill the accelerator's batches,
/// few enough that a wave stays in a core's L2 cache (2 MiB here): about 1 KB a path with its
/// queues (PathState 384 bytes, sampler, first hit, ray, hit, surface, shadow query, draws,
/// shading lanes), so 1 MB at 1024 where 4096 made 4 MB (docs/wavefront.md). Benchmarks of the
/// wavefront's stages feed them waves of this size (bench/surface_bench.cpp).
inline constexpr size_t kPathWaveSize = 1024;

/// Wavefront path tracing: the estimator of `path` (PathEstimator, the same random numbers per
/// pixel sample), but the samples of a batch of pixels advance together one segment at a
/// time, each bounce's rays and shadow rays traced as one batch through
/// Accelerator::intersectBatch / occludedBatch (Laine, Karras & Aila 2013, "Megakernels
/// Considered Harmful"; the CPU form of Mitsuba 3's wavefront variants). docs/wavefront.md.
std::unique_ptr<Integrator> makePathWavefront(const RenderContext& ctx);

}  // namespace tray

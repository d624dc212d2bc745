#pragma once
#include "core/integrator.h"

namespace tray {

/// Wavefront path tracing: the estimator of `path` (PathEstimator, the same random numbers per
/// pixel sample), but the samples of a batch of pixels advance together one segment at a
/// time, each bounce's rays and shadow rays traced as one batch through
/// Accelerator::intersectBatch / occludedBatch (Laine, Karras & Aila 2013, "Megakernels
/// Considered Harmful"; the CPU form of Mitsuba 3's wavefront variants). docs/wavefront.md.
std::unique_ptr<Integrator> makePathWavefront(const RenderContext& ctx);

}  // namespace tray

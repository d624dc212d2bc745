#pragma once
// Rendering in passes: noise-driven adaptive sampling and time limits (docs/adaptive-sampling.md).
// Each pass gives every pixel that wants more one step of samples (render/noise_estimate.h);
// between passes each 8x8 block of image pixels decides which of its pixels go on. Pixels
// keep their counter-based samples, so the image does not depend on the thread count.
#include "core/motion_vectors.h"
#include "render/renderer.h"

namespace tray {

/// Renders samples `range` of each film pixel in passes as options.passes asks; `state` as in
/// renderImage (its progress is created, or resumed from a checkpoint). Called by renderImage,
/// which has checked the region, the state and the AOVs; `vectors` fills the motion layer.
RenderStats renderInPasses(const Integrator& integrator, Film& film, RenderState& state,
                           const RenderOptions& options, SampleRange range,
                           const MotionVectors* vectors);

}  // namespace tray

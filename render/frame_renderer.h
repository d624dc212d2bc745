#pragma once
// Rendering with a frame-level integrator (Integrator::rendersFrames; docs/frame-integrators.md):
// one renderFrame call fills every pixel of the film, which is then written as the tile
// renderer writes its pixels (beauty, AOVs of the first camera hit, Cryptomatte).
#include "core/motion_vectors.h"
#include "render/renderer.h"

namespace tray {

/// Renders the film with integrator.renderFrame; `state` as in renderImage. Called by
/// renderImage, which has checked the region; this checks what a frame render cannot do
/// (sample ranges, noise-driven passes, checkpoints, resuming) and refuses it with one line.
/// `vectors` fills the motion layer.
RenderStats renderFrames(const Integrator& integrator, Film& film, RenderState& state,
                         const RenderOptions& options, const MotionVectors* vectors);

}  // namespace tray

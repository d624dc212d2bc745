#pragma once
// Adaptive supersampling (Whitted 1980, section 4; docs/anti-aliasing.md): trace the pixel's
// corners, subdivide where they differ, recurse to a maximum depth.
#include <memory>

#include "core/film.h"
#include "integrators/integrator.h"

namespace tray {

/// Wraps another integrator (settings.inner) and decides per pixel where its camera rays go.
/// Corners lie on a lattice of (W 2^d + 1) x (H 2^d + 1) points, d = settings.aaDepth; each
/// lattice point is traced exactly once across all threads and pixels (a concurrent map), and
/// its value depends only on its lattice coordinate, so images are thread-count independent.
/// PixelValue::samples is the number of distinct lattice points the pixel used (shared corners
/// included), which the renderer writes to the "samples" AOV.
std::unique_ptr<Integrator> makeAdaptive(const RenderContext& ctx);
/// The same around a given inner integrator (tests wrap a counting one).
std::unique_ptr<Integrator> makeAdaptiveAround(const RenderContext& ctx,
                                               std::unique_ptr<Integrator> inner);

/// The contrast between lattice samples that triggers subdivision: the largest per-channel
/// spread after a display encoding v = (c / (1 + c))^(1/2.2) (Reinhard tone curve + gamma),
/// so it is bounded in [0, 1) and roughly perceptually uniform (a 0.05 step is visible in dark
/// and bright regions alike).
float adaptiveContrast(const Color* colors, int count);

/// Distinct lattice points traced so far by an adaptive integrator (0 for others).
size_t adaptiveTracedPoints(const Integrator& integrator);

/// The --aa-heatmap image: the film's "samples" layer through a colour ramp (dark blue = 1 ray,
/// through green and yellow, to white = the image's maximum), on a log scale. Throws
/// tray::Error when the film has no samples layer.
Film samplesHeatmap(const Film& film);

}  // namespace tray

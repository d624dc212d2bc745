#pragma once
// Adaptive supersampling (Whitted 1980, section 4; docs/anti-aliasing.md): trace the pixel's
// corners, subdivide where they differ, recurse to a maximum depth.
#include <memory>

#include "core/integrator.h"
#include "film/film.h"

namespace tray {

/// Wraps another integrator (option "inner") and decides per pixel where its camera rays go.
/// Corners lie on a lattice of (W 2^d + 1) x (H 2^d + 1) points, d = option "aa-depth"; each
/// lattice point is traced exactly once across all threads and pixels (a concurrent map), and
/// its value depends only on its lattice coordinate, so images are thread-count independent.
/// PixelValue::samples is the number of distinct lattice points the pixel used (shared corners
/// included), which the renderer writes to the "samples" AOV.
std::unique_ptr<Integrator> makeAdaptive(const RenderContext& ctx);
/// Its options: --inner (default whitted), --aa-threshold, --aa-depth, --aa-robust.
const std::vector<OptionSpec>& adaptiveOptions();
/// The same around a given inner integrator (tests wrap a counting one).
std::unique_ptr<Integrator> makeAdaptiveAround(const RenderContext& ctx,
                                               std::unique_ptr<Integrator> inner);

/// The contrast between lattice samples that triggers subdivision: Mitchell's (1987) per-channel
/// Weber-like contrast (max - min) / (max + min + 0.01), largest over R, G, B. It is bounded in
/// [0, 1], relative (a step of 5% matters in shadows and highlights alike, so HDR highlights
/// far above 1 still subdivide), and sees chromatic edges of equal luminance.
float adaptiveContrast(const Color* colors, int count);

/// Lattice points traced so far by an adaptive integrator (0 for others): each once, in a
/// render of the whole image.
size_t adaptiveTracedPoints(const Integrator& integrator);
/// The most lattice points it kept at once (integrators/lattice_cache.h: bands of rows no pixel
/// will read again are dropped).
size_t adaptivePeakKeptPoints(const Integrator& integrator);

/// The --aa-heatmap image: the film's "samples" layer through a colour ramp (dark blue = 1 ray,
/// through green and yellow, to white = the image's maximum), on a log scale. Throws
/// tray::Error when the film has no samples layer.
Film samplesHeatmap(const Film& film);

}  // namespace tray

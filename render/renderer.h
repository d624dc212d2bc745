#pragma once
// The tile loop: every pixel of a film rendered with an integrator, tiles in parallel, with
// progress, checkpoints and a stop flag. The render job (render/render_job.h) drives it.
#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/integrator.h"
#include "film/film.h"
#include "film/render_state.h"
#include "render/image_part.h"
#include "render/noise_estimate.h"
#include "render/render_time.h"

namespace tray {

struct RenderOptions {
  int threads = 0;  ///< 0: all cores
  int tileSize = 16;
  /// AOV layers to fill beside the beauty (names from AovSet::known()).
  std::vector<std::string> aovs;
  /// Ranks per Cryptomatte type (crypto_object, crypto_material in aovs): 2 per EXR layer.
  int cryptomatteRanks = 6;
  /// Called (serialised) after each tile with the fraction done; for progress bars.
  std::function<void(double fraction)> onProgress;
  /// Where the film lies in the integrator's image: film pixel (0, 0) is image pixel
  /// (x0, y0) (region renders). Pixels keep their image coordinates, hence their samples.
  int x0 = 0, y0 = 0;
  /// Renders only these samples of each pixel (none: all of them). Needs an integrator with a
  /// number of samples per pixel (not adaptive, which places its own).
  std::optional<SampleRange> samples;
  /// Set: the samples are given in passes (render/pass_renderer.h): noise-driven adaptive
  /// sampling, a time limit, or both. Needs an integrator with a number of samples per pixel;
  /// its maxSamples is taken from the sample range.
  std::optional<SamplingPasses> passes;
  /// When it becomes true (a signal handler), workers stop after their current pixel (the
  /// wavefront: its current wave of paths); only whole pixels are written.
  const std::atomic<bool>* stop = nullptr;
  /// Every checkpointSeconds (> 0), onCheckpoint gets a copy of the film and state with the
  /// pixels finished so far (called from a worker thread, one call at a time).
  double checkpointSeconds = 0;
  std::function<void(const Film&, const RenderState&)> onCheckpoint;
};

struct RenderStats {
  double seconds = 0;     ///< wall-clock, of the render alone
  double cpuSeconds = 0;  ///< the process's CPU time over the same span (render_time.h)
  RayStats rays;
  bool interrupted = false;  ///< stopped before every pixel was done
  size_t pixelsDone = 0;
  /// Renders in passes: the passes finished, the samples every pixel has (the sum of their
  /// counts) and whether the time limit ended the render.
  int passes = 0;
  uint64_t samples = 0;
  bool timeLimitReached = false;
  double mraysPerSecond() const { return seconds > 0 ? rays.total() / seconds * 1e-6 : 0; }
  RenderTime time() const { return {seconds, cpuSeconds}; }
  void setTime(const RenderTime& t) { seconds = t.seconds, cpuSeconds = t.cpuSeconds; }
};

/// Renders every pixel of the film with the integrator, tiles in parallel (TBB). Each pixel is
/// computed from its own counter-based random numbers, so the image does not depend on the
/// thread count or the order tiles finish in.
RenderStats renderImage(const Integrator& integrator, Film& film,
                        const RenderOptions& options = {});

/// The resumable form. `state` on entry: pixels already done (a checkpoint; empty: none),
/// whose AOVs are in `film` and whose beauty is recomputed from their sums; on return: what
/// is done now. Pixels are rendered whole, so a resumed render equals an uninterrupted one.
RenderStats renderImage(const Integrator& integrator, Film& film, RenderState& state,
                        const RenderOptions& options);

}  // namespace tray

#include "render/frame_renderer.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "core/error.h"
#include "film/aov.h"
#include "film/cryptomatte.h"

namespace tray {
namespace {

/// Throws for what a frame render cannot do, naming the option. Iteration k of a frame-level
/// integrator builds on iteration k - 1 of every pixel, so its work cannot be cut by samples
/// or stopped per pixel, nor taken up again from pixels saved part-way.
void checkFrameRender(const Integrator& integrator, const RenderState& state,
                      const RenderOptions& options) {
  const std::string name = integrator.context().settings.getString("integrator");
  if (options.samples) {
    std::string m = "--sample-range: ";
    m += name;
    m += " renders whole frames (each iteration builds on the one before), so its renders "
         "cannot be split by samples (split them with --region)";
    throw Error(m);
  }
  if (options.passes && options.passes->threshold > 0) {
    std::string m = "--noise-threshold: ";
    m += name;
    m += " renders every pixel in every iteration; it has no per-pixel adaptive sampling";
    throw Error(m);
  }
  if (options.checkpointSeconds > 0 ||
      std::any_of(state.done.begin(), state.done.end(), [](uint8_t d) { return d != 0; })) {
    std::string m = "--checkpoint/--resume: ";
    m += name;
    m += " keeps its progress in memory between iterations and cannot resume from a checkpoint";
    throw Error(m);
  }
  if (AovSet::wantsLightPaths(options.aovs)) {
    std::string m =
        "--aov: the light-path layers (lightpaths, diffuse_direct, ...) are not "
        "filled by ";
    m += name;
    m += "; they need --integrator path or path-wavefront";
    throw Error(m);
  }
}

}  // namespace

RenderStats renderFrames(const Integrator& integrator, Film& film, RenderState& state,
                         const RenderOptions& options, const MotionVectors* vectors) {
  checkFrameRender(integrator, state, options);
  const RenderClock clock;
  const AovSet aovs(film, options.aovs, vectors);
  const Cryptomatte crypto(film, integrator.context().scene, options.aovs,
                           options.cryptomatteRanks);
  FrameTask task;
  task.x0 = options.x0, task.y0 = options.y0;
  task.width = film.width(), task.height = film.height();
  task.timeLimit = options.passes ? options.passes->timeLimit : 0.0;
  task.stop = options.stop;
  task.onProgress = options.onProgress;
  task.wantsIds = crypto.active();
  std::vector<FramePixel> pixels(size_t(task.width) * task.height);
  FrameResult done;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] { done = integrator.renderFrame(task, pixels); });

  const bool valid = done.iterations > 0;
  for (size_t p = 0; p < pixels.size() && valid; ++p) {
    const int x = int(p % size_t(task.width)), y = int(p / size_t(task.width));
    const FramePixel& px = pixels[p];
    state.sums[p] = px.sums;
    state.done[p] = 1;
    writeBeauty(film, x, y, px.sums);
    PixelValue v;
    v.radiance = px.sums.radiance();
    v.alpha = px.sums.coverage();
    v.primary = px.first;
    v.samples = px.samples;
    aovs.write(film, x, y, v, nullptr);
    if (task.wantsIds) crypto.write(film, x, y, px.coverage);
  }
  RenderStats stats;
  stats.rays = done.rays;
  stats.passes = done.iterations;
  for (const FramePixel& px : pixels) stats.samples += px.samples;  // the summary's average
  stats.timeLimitReached = done.timeLimitReached;
  stats.pixelsDone = valid ? pixels.size() : 0;
  stats.interrupted = done.stopped;
  stats.setTime(clock.elapsed());
  return stats;
}

}  // namespace tray

#include "core/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "core/aov.h"
#include "core/cryptomatte.h"
#include "core/error.h"

namespace tray {
namespace {

using Clock = std::chrono::steady_clock;

void writeBeauty(Film& film, int x, int y, const PixelSums& s) {
  const Color c = s.radiance();
  float* px = film.pixel(Film::kBeauty, x, y);
  px[0] = c.x, px[1] = c.y, px[2] = c.z, px[3] = s.coverage();
}

/// A copy of the pixels published as done (acquire: their film and sums writes are visible);
/// the others read as zero, so the copy never races with workers writing them.
void snapshot(const Film& film, const RenderState& state, const std::atomic<uint8_t>* done,
              Film& outFilm, RenderState& outState) {
  outFilm = Film(film.width(), film.height());
  for (const FilmLayer& l : film.layers()) outFilm.addLayer(l.name, l.channels);
  for (const auto& [key, value] : film.metadata()) outFilm.setMetadata(key, value);
  outState = RenderState::empty(state.sums.size());
  for (size_t p = 0; p < state.sums.size(); ++p) {
    const int x = int(p % film.width()), y = int(p / film.width());
    const bool finished = done[p].load(std::memory_order_acquire);
    for (size_t l = 0; l < film.layers().size(); ++l) {
      float* out = outFilm.pixel(int(l), x, y);
      const size_t nc = film.layers()[l].channels.size();
      if (finished)
        for (size_t c = 0; c < nc; ++c) out[c] = film.pixel(int(l), x, y)[c];
    }
    if (finished) outState.sums[p] = state.sums[p], outState.done[p] = 1;
  }
}

}  // namespace

RenderStats renderImage(const Integrator& integrator, Film& film, const RenderOptions& options) {
  RenderState state;
  return renderImage(integrator, film, state, options);
}

RenderStats renderImage(const Integrator& integrator, Film& film, RenderState& state,
                        const RenderOptions& options) {
  const RenderContext& ctx = integrator.context();
  if (options.x0 < 0 || options.y0 < 0 || options.x0 + film.width() > ctx.width ||
      options.y0 + film.height() > ctx.height)
    throw Error("the region lies outside the image", Error::Kind::kRender);
  const int spp = integrator.samplesPerPixel();
  const int sampleEnd = options.sampleEnd > 0 ? options.sampleEnd : spp;
  const bool ranged = options.sampleBegin != 0 || sampleEnd != spp;
  if (ranged &&
      (spp == 0 || options.sampleBegin < 0 || options.sampleBegin >= sampleEnd || sampleEnd > spp))
    throw Error("sample range outside the integrator's samples", Error::Kind::kRender);

  const size_t pixels = size_t(film.width()) * film.height();
  if (state.done.empty()) state = RenderState::empty(pixels);
  if (state.sums.size() != pixels || state.done.size() != pixels)
    throw Error("the render state does not match the film", Error::Kind::kRender);
  if (AovSet::wantsLightPaths(options.aovs) && !integrator.splitsLightPaths())
    throw Error(
        "--aov: the light-path layers (lightpaths, diffuse_direct, ...) need "
        "--integrator path or path-wavefront");
  std::optional<MotionVectors> vectors;  // only when the motion layer is asked for
  if (std::count(options.aovs.begin(), options.aovs.end(), "motion"))
    vectors.emplace(ctx.scene, ctx.camera.desc(), ctx.width, ctx.height);
  const AovSet aovs(film, options.aovs, vectors ? &*vectors : nullptr);
  std::unique_ptr<std::atomic<uint8_t>[]> done(new std::atomic<uint8_t>[pixels]);
  for (size_t p = 0; p < pixels; ++p) {
    done[p].store(state.done[p], std::memory_order_relaxed);
    if (state.done[p])
      writeBeauty(film, int(p % film.width()), int(p / film.width()), state.sums[p]);
  }

  const int ts = std::max(1, options.tileSize);
  const int tilesX = (film.width() + ts - 1) / ts, tilesY = (film.height() + ts - 1) / ts;
  const int tileCount = tilesX * tilesY;
  RenderStats result;
  const Cryptomatte crypto(film, ctx.scene, options.aovs, options.cryptomatteRanks);
  std::mutex mutex;
  int tilesDone = 0;
  bool checkpointing = false;
  const auto start = Clock::now();
  auto lastCheckpoint = start;

  auto stopped = [&] { return options.stop && options.stop->load(std::memory_order_relaxed); };
  // Writes a rendered pixel (film coordinates) and publishes it as done. `averaged` (when not
  // null) holds the AOVs averaged over all samples.
  auto finishPixel = [&](int x, int y, const PixelSums& sums, const PixelValue& v,
                         const IdCoverage* ids, const AovSums* averaged) {
    const size_t p = size_t(y) * film.width() + x;
    state.sums[p] = sums;
    writeBeauty(film, x, y, sums);
    aovs.write(film, x, y, v, averaged);
    if (ids) crypto.write(film, x, y, *ids);
    done[p].store(1, std::memory_order_release);
  };
  // The integrator places its own samples: its mean, weight 1 (exact in double).
  auto renderOwnSamples = [&](int x, int y, RayStats& stats, IdCoverage& coverage) {
    coverage.clear();
    IdCoverage* ids = crypto.active() ? &coverage : nullptr;
    PixelValue v = integrator.renderPixel(x + options.x0, y + options.y0, stats, ids);
    PixelSums sums;
    sums.rgb[0] = v.radiance.x, sums.rgb[1] = v.radiance.y, sums.rgb[2] = v.radiance.z;
    sums.alpha = v.alpha, sums.weight = 1;
    finishPixel(x, y, sums, v, ids, nullptr);
  };
  // Pixels go to the integrator in batches of its pixelBatch() (1: one at a time); tasks hold
  // image coordinates, so pixels keep their samples in region renders.
  const size_t batch = size_t(std::max(1, integrator.pixelBatch()));
  auto renderBatch = [&](std::vector<PixelTask>& tasks, RayStats& stats) {
    if (tasks.empty()) return;
    integrator.accumulatePixels(tasks, options.sampleBegin, sampleEnd, stats, options.stop);
    for (const PixelTask& t : tasks) {
      if (!t.finished) continue;  // stopped before its last sample: left to a resume
      PixelValue v;
      v.primary = t.first;
      v.samples = t.samples;
      finishPixel(t.x - options.x0, t.y - options.y0, t.sums, v, t.coverage, t.aovSums);
    }
    tasks.clear();
  };

  auto renderTile = [&](int tile) {
    RayStats local;
    // Per pixel of a batch, reused across batches: Cryptomatte's ids (only filled for
    // Cryptomatte) and the AOVs averaged over all samples (only where accumulate() places the
    // samples).
    std::vector<IdCoverage> coverage(spp > 0 ? batch : 1);
    std::vector<AovSums> aovSums(spp > 0 && aovs.averaged() ? batch : 0);
    for (AovSums& a : aovSums) aovs.configure(a);
    std::vector<PixelTask> tasks;
    const int x0 = (tile % tilesX) * ts, y0 = (tile / tilesX) * ts;
    const int x1 = std::min(x0 + ts, film.width()), y1 = std::min(y0 + ts, film.height());
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        if (stopped()) break;
        if (done[size_t(y) * film.width() + x].load(std::memory_order_relaxed)) continue;
        if (spp == 0) {
          renderOwnSamples(x, y, local, coverage[0]);
          continue;
        }
        PixelTask& t = tasks.emplace_back();
        t.x = x + options.x0, t.y = y + options.y0;
        const size_t slot = tasks.size() - 1;
        IdCoverage& ids = coverage[slot];
        ids.clear();
        t.coverage = crypto.active() ? &ids : nullptr;
        if (!aovSums.empty()) {
          aovSums[slot].clear();
          t.aovSums = &aovSums[slot];
        }
        if (tasks.size() == batch) renderBatch(tasks, local);
      }
    if (!stopped()) renderBatch(tasks, local);
    bool checkpointNow = false;
    {
      std::lock_guard<std::mutex> lock(mutex);
      result.rays += local;
      ++tilesDone;
      if (options.onProgress) options.onProgress(double(tilesDone) / tileCount);
      const auto now = Clock::now();
      if (options.onCheckpoint && options.checkpointSeconds > 0 && !checkpointing &&
          std::chrono::duration<double>(now - lastCheckpoint).count() >=
              options.checkpointSeconds &&
          tilesDone < tileCount && !stopped()) {
        checkpointing = checkpointNow = true;
        lastCheckpoint = now;
      }
    }
    if (checkpointNow) {  // outside the lock: other tiles go on while the file is written
      Film copy(1, 1);
      RenderState copyState;
      snapshot(film, state, done.get(), copy, copyState);
      options.onCheckpoint(copy, copyState);
      std::lock_guard<std::mutex> lock(mutex);
      checkpointing = false;
    }
  };

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tileCount, 1),
                      [&](const tbb::blocked_range<int>& r) {
                        for (int t = r.begin(); t != r.end(); ++t) renderTile(t);
                      });
  });
  for (size_t p = 0; p < pixels; ++p) state.done[p] = done[p].load(std::memory_order_relaxed);
  result.pixelsDone = state.pixelsDone();
  result.interrupted = result.pixelsDone < pixels;
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace tray

#include "render/renderer.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "core/error.h"
#include "film/aov.h"
#include "film/cryptomatte.h"
#include "render/checkpoint_clock.h"
#include "render/frame_renderer.h"
#include "render/pass_renderer.h"
#include "render/tile_grid.h"

namespace tray {
namespace {


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

/// The samples of each pixel to render: none when the integrator places its own (adaptive),
/// else options.samples or all of them. Throws for a range the integrator does not have.
std::optional<SampleRange> samplesOf(const Integrator& integrator, const RenderOptions& options) {
  const std::optional<int> spp = integrator.samplesPerPixel();
  if (!options.samples) return spp ? std::optional(SampleRange{0, *spp}) : std::nullopt;
  const SampleRange r = *options.samples;
  if (spp && r.begin == 0 && r.end == *spp) return r;  // all of them
  if (!spp || r.begin < 0 || r.begin >= r.end || r.end > *spp)
    throw Error("sample range outside the integrator's samples", Error::Kind::kRender);
  return r;
}

/// Throws unless the film (a region at options.x0, y0) lies inside the integrator's image.
void checkRegion(const Integrator& integrator, const Film& film, const RenderOptions& options) {
  const RenderContext& ctx = integrator.context();
  if (options.x0 < 0 || options.y0 < 0 || options.x0 + film.width() > ctx.width ||
      options.y0 + film.height() > ctx.height)
    throw Error("the region lies outside the image", Error::Kind::kRender);
}

/// Throws unless the state matches the film and the integrator makes the AOVs asked for.
void checkStateAndAovs(const Integrator& integrator, const Film& film, const RenderState& state,
                       const RenderOptions& options) {
  const size_t pixels = size_t(film.width()) * film.height();
  if (state.sums.size() != pixels || state.done.size() != pixels)
    throw Error("the render state does not match the film", Error::Kind::kRender);
  if (AovSet::wantsLightPaths(options.aovs) && !integrator.splitsLightPaths())
    throw Error(
        "--aov: the light-path layers (lightpaths, diffuse_direct, ...) need "
        "--integrator path or path-wavefront");
  if (!options.passes) return;
  if (!integrator.samplesPerPixel())
    throw Error(
        "--noise-threshold and --time-limit need an integrator with samples per pixel "
        "(path, path-wavefront, whitted): this one places its own");
  if (AovSet::wantsLightPaths(options.aovs))
    throw Error(
        "--aov: the light-path layers must add up to the beauty over every sample, which a "
        "render in passes (--noise-threshold, --time-limit) does not keep: render them with "
        "a fixed --spp");
}

/// Motion vectors, only when the motion layer is asked for.
std::optional<MotionVectors> motionVectorsFor(const RenderContext& ctx,
                                              const std::vector<std::string>& aovs) {
  std::optional<MotionVectors> vectors;
  if (std::count(aovs.begin(), aovs.end(), "motion"))
    vectors.emplace(ctx.scene, ctx.camera.desc(), ctx.width, ctx.height);
  return vectors;
}

/// One renderImage call: the film, its state and the tiles the worker threads share.
class TileRenderer {
 public:
  /// `samples`: samplesOf(integrator, options).
  TileRenderer(const Integrator& integrator, Film& film, RenderState& state,
               const RenderOptions& options, std::optional<SampleRange> samples)
      : integrator_(integrator),
        film_(film),
        state_(state),
        options_(options),
        samples_(samples),
        vectors_(motionVectorsFor(integrator.context(), options.aovs)),
        aovs_(film, options.aovs, vectors_ ? &*vectors_ : nullptr),
        crypto_(film, integrator.context().scene, options.aovs, options.cryptomatteRanks),
        batch_(size_t(std::max(1, integrator.pixelBatch()))),
        tiles_(film.width(), film.height(), options.tileSize),
        done_(new std::atomic<uint8_t>[state.done.size()]) {
    for (size_t p = 0; p < state.done.size(); ++p) {  // resumed pixels: their beauty again
      done_[p].store(state.done[p], std::memory_order_relaxed);
      if (state.done[p])
        writeBeauty(film, int(p % film.width()), int(p / film.width()), state.sums[p]);
    }
  }

  RenderStats run() {
    clock_.restart();
    checkpoints_.start(clock_.started());
    tbb::task_arena arena(options_.threads > 0 ? options_.threads : tbb::task_arena::automatic);
    arena.execute([&] { tiles_.forEach([&](int t) { renderTile(t); }); });
    const size_t pixels = state_.done.size();
    for (size_t p = 0; p < pixels; ++p) state_.done[p] = done_[p].load(std::memory_order_relaxed);
    result_.pixelsDone = state_.pixelsDone();
    result_.interrupted = result_.pixelsDone < pixels;
    result_.setTime(clock_.elapsed());
    return result_;
  }

 private:
  /// What one tile's worker reuses from pixel to pixel: per pixel of a batch, Cryptomatte's
  /// ids (only filled for Cryptomatte) and the AOVs averaged over all samples (only where
  /// accumulate() places the samples).
  struct TileWork {
    RayStats rays;
    std::vector<IdCoverage> coverage;
    std::vector<AovSums> aovSums;
    std::vector<PixelTask> tasks;
  };

  bool stopped() const { return options_.stop && options_.stop->load(std::memory_order_relaxed); }

  /// Writes a rendered pixel (film coordinates) and publishes it as done. `averaged` (when not
  /// null) holds the AOVs averaged over all samples.
  void finishPixel(int x, int y, const PixelSums& sums, const PixelValue& v, const IdCoverage* ids,
                   const AovSums* averaged) {
    const size_t p = size_t(y) * film_.width() + x;
    state_.sums[p] = sums;
    writeBeauty(film_, x, y, sums);
    aovs_.write(film_, x, y, v, averaged);
    if (ids) crypto_.write(film_, x, y, *ids);
    done_[p].store(1, std::memory_order_release);
  }

  /// The integrator places its own samples: its mean, weight 1 (exact in double).
  void renderOwnSamples(int x, int y, TileWork& work) {
    IdCoverage& coverage = work.coverage[0];
    coverage.clear();
    IdCoverage* ids = crypto_.active() ? &coverage : nullptr;
    PixelValue v = integrator_.renderPixel(x + options_.x0, y + options_.y0, work.rays, ids);
    PixelSums sums;
    sums.rgb[0] = v.radiance.x, sums.rgb[1] = v.radiance.y, sums.rgb[2] = v.radiance.z;
    sums.alpha = v.alpha, sums.weight = 1;
    finishPixel(x, y, sums, v, ids, nullptr);
  }

  /// Adds pixel (x, y) to the batch, rendering the batch once it is full. Tasks hold image
  /// coordinates, so pixels keep their samples in region renders.
  void queuePixel(int x, int y, TileWork& work) {
    PixelTask& t = work.tasks.emplace_back();
    t.x = x + options_.x0, t.y = y + options_.y0;
    const size_t slot = work.tasks.size() - 1;
    IdCoverage& ids = work.coverage[slot];
    ids.clear();
    t.coverage = crypto_.active() ? &ids : nullptr;
    if (!work.aovSums.empty()) {
      work.aovSums[slot].clear();
      t.aovSums = &work.aovSums[slot];
    }
    if (work.tasks.size() == batch_) renderBatch(work);
  }

  /// The batch's samples, through the integrator's accumulatePixels (a wavefront traces them
  /// together).
  void renderBatch(TileWork& work) {
    if (work.tasks.empty()) return;
    integrator_.accumulatePixels(work.tasks, samples_->begin, samples_->end, work.rays,
                                 options_.stop);
    for (const PixelTask& t : work.tasks) {
      if (!t.finished) continue;  // stopped before its last sample: left to a resume
      PixelValue v;
      v.primary = t.first;
      v.samples = t.samples;
      finishPixel(t.x - options_.x0, t.y - options_.y0, t.sums, v, t.coverage, t.aovSums);
    }
    work.tasks.clear();
  }

  void renderTile(int tile) {
    TileWork work;
    work.coverage.resize(samples_ ? batch_ : 1);
    work.aovSums.resize(samples_ && aovs_.averaged() ? batch_ : 0);
    for (AovSums& a : work.aovSums) aovs_.configure(a);
    const TileGrid::Tile at = tiles_.at(tile);
    for (int y = at.y0; y < at.y1; ++y)
      for (int x = at.x0; x < at.x1; ++x) {
        if (stopped()) break;
        if (done_[size_t(y) * film_.width() + x].load(std::memory_order_relaxed)) continue;
        if (samples_)
          queuePixel(x, y, work);
        else
          renderOwnSamples(x, y, work);
      }
    if (!stopped()) renderBatch(work);
    if (tileFinished(work.rays)) writeCheckpoint();
  }

  /// Counts a finished tile, reports progress and returns whether a checkpoint is due (and now
  /// this worker's to write).
  bool tileFinished(const RayStats& rays) {
    std::lock_guard<std::mutex> lock(mutex_);
    result_.rays += rays;
    ++tilesDone_;
    if (options_.onProgress) options_.onProgress(double(tilesDone_) / tiles_.count());
    return checkpoints_.claim(tilesDone_ >= tiles_.count() || stopped());
  }

  /// Outside the lock: other tiles go on while the file is written.
  void writeCheckpoint() {
    Film copy(1, 1);
    RenderState copyState;
    snapshot(film_, state_, done_.get(), copy, copyState);
    options_.onCheckpoint(copy, copyState);
    std::lock_guard<std::mutex> lock(mutex_);
    checkpoints_.release();
  }

  const Integrator& integrator_;
  Film& film_;
  RenderState& state_;
  const RenderOptions& options_;
  const std::optional<SampleRange> samples_;  ///< none: the integrator places its own
  const std::optional<MotionVectors> vectors_;
  const AovSet aovs_;
  const Cryptomatte crypto_;
  const size_t batch_;  ///< pixels given to accumulatePixels at once (its pixelBatch())
  const TileGrid tiles_;
  std::unique_ptr<std::atomic<uint8_t>[]> done_;  ///< published pixels (acquire / release)

  std::mutex mutex_;  ///< guards what follows
  RenderStats result_;
  int tilesDone_ = 0;
  CheckpointClock checkpoints_{options_};
  RenderClock clock_;
};

}  // namespace

RenderStats renderImage(const Integrator& integrator, Film& film, const RenderOptions& options) {
  RenderState state;
  return renderImage(integrator, film, state, options);
}

RenderStats renderImage(const Integrator& integrator, Film& film, RenderState& state,
                        const RenderOptions& options) {
  checkRegion(integrator, film, options);
  if (integrator.rendersFrames()) {  // docs/frame-integrators.md
    if (state.done.empty()) state = RenderState::empty(size_t(film.width()) * film.height());
    const std::optional<MotionVectors> vectors =
        motionVectorsFor(integrator.context(), options.aovs);
    return renderFrames(integrator, film, state, options, vectors ? &*vectors : nullptr);
  }
  const std::optional<SampleRange> samples = samplesOf(integrator, options);
  if (state.done.empty()) state = RenderState::empty(size_t(film.width()) * film.height());
  checkStateAndAovs(integrator, film, state, options);
  if (options.passes) {
    const std::optional<MotionVectors> vectors =
        motionVectorsFor(integrator.context(), options.aovs);
    return renderInPasses(integrator, film, state, options, *samples,
                          vectors ? &*vectors : nullptr);
  }
  TileRenderer tiles(integrator, film, state, options, samples);
  return tiles.run();
}

}  // namespace tray

#include "render/pass_renderer.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

#include "film/aov.h"
#include "film/cryptomatte.h"
#include "render/checkpoint_clock.h"
#include "render/noise_estimate.h"
#include "render/tile_grid.h"

namespace tray {
namespace {


/// The steps of a batch of pixels under way: `second` holds each pixel's step (a first step:
/// its second half; `first` then its first half, which becomes its earlier mean) and, for a
/// first step, the ids and averaged AOVs gathered over both halves.
struct StepTasks {
  std::vector<PixelTask> first, second;
  std::vector<IdCoverage> coverage;
  std::vector<AovSums> aovSums;
};

class PassRenderer {
 public:
  PassRenderer(const Integrator& integrator, Film& film, RenderState& state,
               const RenderOptions& options, SampleRange range, const MotionVectors* vectors)
      : integrator_(integrator),
        film_(film),
        state_(state),
        options_(options),
        begin_(range.begin),
        passes_(passesOf(*options.passes, range)),
        aovs_(film, options.aovs, vectors),
        crypto_(film, integrator.context().scene, options.aovs, options.cryptomatteRanks),
        samplesLayer_(film.findLayer("samples")),
        tiles_(film.width(), film.height(), options.tileSize) {
    const size_t n = state.sums.size();
    if (state.progress.size() != n) state.progress.assign(n, PixelProgress{});
    for (size_t p = 0; p < n; ++p)  // resumed pixels: their beauty again
      if (state.progress[p].count > 0) writeBeauty(film, x(p), y(p), state.sums[p]);
  }

  RenderStats run() {
    clock_.restart();
    checkpoints_.start(clock_.started());
    std::thread watcher([this] { watch(); });
    tbb::task_arena arena(options_.threads > 0 ? options_.threads : tbb::task_arena::automatic);
    arena.execute([&] {
      // A checkpoint taken mid-pass owes its pending pixels their step before anyone decides.
      bool owed = std::any_of(state_.progress.begin(), state_.progress.end(),
                              [](const PixelProgress& g) { return g.pending; });
      while (!signalled() && (owed || decide())) {
        owed = false;
        firstPassDone_.store(everyPixelSampled());  // a resumed render may have done it
        tiles_.forEach([&](int t) { renderTile(t); });
        if (!stopNow_.load()) ++result_.passes;
      }
    });
    {
      std::lock_guard<std::mutex> lock(watchMutex_);
      finished_ = true;
    }
    watchWake_.notify_all();
    watcher.join();
    return finish();
  }

 private:
  static SamplingPasses passesOf(SamplingPasses p, SampleRange range) {
    p.maxSamples = range.end - range.begin;
    p.minSamples = std::clamp(p.minSamples, 1, p.maxSamples);
    return p;
  }
  int x(size_t p) const { return int(p % film_.width()); }
  int y(size_t p) const { return int(p / film_.width()); }

  bool everyPixelSampled() const {
    return std::all_of(state_.progress.begin(), state_.progress.end(),
                       [](const PixelProgress& g) { return g.count > 0; });
  }

  /// Stops the render when the signal flag rises, or once the first pass is done and the time
  /// limit has passed.
  void watch() {
    std::unique_lock<std::mutex> lock(watchMutex_);
    while (!finished_) {
      signalled();
      const double elapsed = clock_.elapsed().seconds;
      if (passes_.timeLimit > 0 && firstPassDone_.load() && elapsed >= passes_.timeLimit) {
        timeUp_.store(true);
        stopNow_.store(true);
      }
      watchWake_.wait_for(lock, std::chrono::milliseconds(5));
    }
  }

  /// Whether the render stops now; a raised signal flag stops it (also seen between steps,
  /// not only by the watcher).
  bool signalled() {
    if (options_.stop && options_.stop->load(std::memory_order_relaxed)) {
      signalled_.store(true);
      stopNow_.store(true);
    }
    return stopNow_.load();
  }

  /// Each block of image pixels decides which of its film pixels take a step (sets pending);
  /// false when none does. Also counts the samples the progress fraction credits.
  bool decide() {
    const int bx0 = options_.x0 / kNoiseBlock, by0 = options_.y0 / kNoiseBlock;
    const int bx1 = (options_.x0 + film_.width() - 1) / kNoiseBlock;
    const int by1 = (options_.y0 + film_.height() - 1) / kNoiseBlock;
    // Rows of blocks in parallel (each block decides alone); their sums added in row order.
    std::vector<uint64_t> credited(size_t(by1 - by0 + 1));
    std::vector<uint8_t> any(credited.size());
    tbb::parallel_for(by0, by1 + 1, [&](int by) {
      BlockScratch scratch;
      for (int bx = bx0; bx <= bx1; ++bx)
        any[by - by0] |= decideBlockAt(bx, by, scratch, credited[by - by0]);
    });
    credited_ = 0;
    for (uint64_t c : credited) credited_ += c;
    return std::any_of(any.begin(), any.end(), [](uint8_t a) { return a != 0; });
  }

  struct BlockScratch {
    std::vector<float> error;
    std::vector<uint32_t> count;
    std::vector<uint8_t> more;
  };

  /// Block (bx, by) of image pixels decides for its pixels inside the film (sets pending);
  /// adds the samples the progress credits them to `credited`; true when one goes on.
  bool decideBlockAt(int bx, int by, BlockScratch& b, uint64_t& credited) {
    const int fx0 = std::max(bx * kNoiseBlock - options_.x0, 0);
    const int fy0 = std::max(by * kNoiseBlock - options_.y0, 0);
    const int fx1 = std::min((bx + 1) * kNoiseBlock - options_.x0, film_.width());
    const int fy1 = std::min((by + 1) * kNoiseBlock - options_.y0, film_.height());
    const int w = fx1 - fx0, h = fy1 - fy0;
    b.error.resize(size_t(w) * h), b.count.resize(b.error.size()), b.more.resize(b.error.size());
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const size_t p = size_t(fy0 + j) * film_.width() + fx0 + i;
        const PixelProgress& g = state_.progress[p];
        const int n = int(g.count);
        b.error[j * w + i] =
            pixelError(state_.sums[p], g.half, n, earlierCount(n, passes_), passes_.absoluteError);
        b.count[j * w + i] = g.count;
      }
    decideBlock(b.error, b.count, w, h, passes_, b.more);
    bool any = false;
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        PixelProgress& g = state_.progress[size_t(fy0 + j) * film_.width() + fx0 + i];
        g.pending = b.more[j * w + i];
        any = any || g.pending;
        credited += g.pending ? g.count : uint64_t(passes_.maxSamples);
      }
    return any;
  }

  /// The pending pixels of one tile, grouped by their sample count (a group shares its step's
  /// sample range) and traced in batches of the integrator's size.
  void renderTile(int tile) {
    const TileGrid::Tile at = tiles_.at(tile);
    std::vector<size_t> pending;
    for (int yy = at.y0; yy < at.y1; ++yy)
      for (int xx = at.x0; xx < at.x1; ++xx) {
        const size_t p = size_t(yy) * film_.width() + xx;
        if (state_.progress[p].pending) pending.push_back(p);
      }
    std::stable_sort(pending.begin(), pending.end(), [&](size_t a, size_t b) {
      return state_.progress[a].count < state_.progress[b].count;
    });
    const size_t batch = size_t(std::max(1, integrator_.pixelBatch()));
    RayStats rays;
    StepTasks work;
    for (size_t i = 0; i < pending.size() && !signalled();) {
      const uint32_t count = state_.progress[pending[i]].count;
      size_t j = i;
      while (j < pending.size() && j - i < batch && state_.progress[pending[j]].count == count) ++j;
      renderStep(std::span(pending).subspan(i, j - i), int(count), work, rays);
      i = j;
    }
    const bool checkpoint = tileFinished(rays);
    if (checkpoint) writeCheckpoint();
  }

  /// One step of `pixels` (all with `count` samples), traced in one go (the first step in two
  /// halves, the first of which is its earlier mean), then committed.
  void renderStep(std::span<const size_t> pixels, int count, StepTasks& work, RayStats& rays) {
    const int step = nextStep(count, passes_);
    const int half = count == 0 ? step / 2 : 0;  // samples of the first half-call, if any
    const bool firstStep = count == 0;
    work.first.assign(half > 0 ? pixels.size() : 0, PixelTask{});
    work.second.assign(pixels.size(), PixelTask{});
    work.coverage.resize(pixels.size());
    work.aovSums.resize(firstStep && aovs_.averaged() ? pixels.size() : 0);
    auto prepare = [&](PixelTask& t, size_t k) {
      t.x = x(pixels[k]) + options_.x0, t.y = y(pixels[k]) + options_.y0;
      if (firstStep && crypto_.active()) t.coverage = &work.coverage[k];
      if (!work.aovSums.empty()) t.aovSums = &work.aovSums[k];
    };
    for (size_t k = 0; k < pixels.size(); ++k) {
      if (half > 0) prepare(work.first[k], k);  // only a first step has two halves
      prepare(work.second[k], k);
      work.coverage[k].clear();
      if (!work.aovSums.empty()) aovs_.configure(work.aovSums[k]), work.aovSums[k].clear();
    }
    const int from = begin_ + count;
    if (half > 0) integrator_.accumulatePixels(work.first, from, from + half, rays, &stopNow_);
    integrator_.accumulatePixels(work.second, from + half, from + step, rays, &stopNow_);
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t k = 0; k < pixels.size(); ++k)
      if ((half == 0 || work.first[k].finished) && work.second[k].finished)
        commit(pixels[k], step, half, work, k);
  }

  /// Adds a traced step to pixel p and writes it (under mutex_: checkpoints copy the film).
  /// The earlier mean becomes the first half (first step) or the sums before the step.
  void commit(size_t p, int step, int half, const StepTasks& work, size_t k) {
    PixelProgress& g = state_.progress[p];
    const PixelTask* a = half > 0 ? &work.first[k] : nullptr;  // the first half, if any
    const PixelTask& b = work.second[k];
    if (a) {
      g.half = a->sums;
      state_.sums[p] += a->sums;
    } else {
      g.half = state_.sums[p];
    }
    state_.sums[p] += b.sums;
    const int px = x(p), py = y(p);
    writeBeauty(film_, px, py, state_.sums[p]);
    if (g.count == 0) {  // the AOVs other than the beauty come from the first step
      PixelValue v;
      v.primary = a ? a->first : b.first;
      aovs_.write(film_, px, py, v, work.aovSums.empty() ? nullptr : &work.aovSums[k]);
      if (crypto_.active()) crypto_.write(film_, px, py, work.coverage[k]);
    }
    g.count += uint32_t(step);
    g.pending = false;
    if (samplesLayer_ >= 0) film_.pixel(samplesLayer_, px, py)[0] = float(g.count);
    credited_ += uint64_t(step);
  }

  /// Counts a tile's rays, reports progress and returns whether a checkpoint is due (and now
  /// this worker's to write).
  bool tileFinished(const RayStats& rays) {
    std::lock_guard<std::mutex> lock(mutex_);
    result_.rays += rays;
    const double budget = double(state_.sums.size()) * passes_.maxSamples;
    fraction_ = std::max(fraction_, std::min(1.0, double(credited_) / budget));
    if (options_.onProgress) options_.onProgress(fraction_);
    return checkpoints_.claim(stopNow_.load());
  }

  /// A copy of the film and state as committed so far (under mutex_), written outside it.
  void writeCheckpoint() {
    Film copy(1, 1);
    RenderState copyState;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      copy = film_, copyState = state_;
    }
    options_.onCheckpoint(copy, copyState);
    std::lock_guard<std::mutex> lock(mutex_);
    checkpoints_.release();
  }

  /// The outcome: a signal leaves every pixel undone and the progress to resume; the end of
  /// the passes or of the time drops the steps not taken and marks every pixel done.
  RenderStats finish() {
    result_.setTime(clock_.elapsed());
    for (const PixelProgress& g : state_.progress) result_.samples += g.count;
    result_.timeLimitReached = timeUp_ && !signalled_;
    if (signalled_) {
      result_.interrupted = true;
      return result_;
    }
    for (PixelProgress& g : state_.progress) g.pending = false;
    std::fill(state_.done.begin(), state_.done.end(), uint8_t(1));
    result_.pixelsDone = state_.done.size();
    return result_;
  }

  const Integrator& integrator_;
  Film& film_;
  RenderState& state_;
  const RenderOptions& options_;
  const int begin_;  ///< the range's first sample
  const SamplingPasses passes_;
  const AovSet aovs_;
  const Cryptomatte crypto_;
  const int samplesLayer_;  ///< the samples AOV's layer, or -1
  const TileGrid tiles_;

  std::atomic<bool> stopNow_{false};  ///< a signal or the time limit: workers stop
  std::atomic<bool> firstPassDone_{false};
  std::atomic<bool> signalled_{false}, timeUp_{false};  ///< why stopNow_ rose
  std::mutex watchMutex_;                               ///< guards finished_ (the watcher's)
  std::condition_variable watchWake_;
  bool finished_ = false;

  std::mutex mutex_;  ///< guards the film, the state and what follows
  RenderStats result_;
  uint64_t credited_ = 0;  ///< samples the progress counts (settled pixels count in full)
  double fraction_ = 0;
  CheckpointClock checkpoints_{options_};
  RenderClock clock_;
};

}  // namespace

RenderStats renderInPasses(const Integrator& integrator, Film& film, RenderState& state,
                           const RenderOptions& options, SampleRange range,
                           const MotionVectors* vectors) {
  PassRenderer passes(integrator, film, state, options, range, vectors);
  return passes.run();
}

}  // namespace tray

#include "integrators/bdpt.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "integrators/bdpt_tracer.h"
#include "integrators/path.h"

namespace tray {
namespace {

/// Light paths per chunk of the light-tracing pass: each chunk's splats go to a buffer of its
/// own, and the buffers are added to the pixels in chunk order.
constexpr uint32_t kChunkPaths = 4096;
/// Chunks traced (in parallel) before their buffers are reduced: bounds the buffers' memory.
constexpr size_t kChunksPerBatch = 256;
/// Mixed into the seed of the light-tracing pass's samplers, so that light path j of sample i
/// draws other numbers than pixel j's camera sample i.
constexpr uint64_t kLightPassSeed = 0x6c8e9cf570932bd5ull;

BdptStrategies strategiesOf(const std::string& name) {
  if (name == "s0") return BdptStrategies::kS0;
  if (name == "s1") return BdptStrategies::kS1;
  if (name == "t1") return BdptStrategies::kT1;
  return BdptStrategies::kAll;
}

/// BDPT as a frame-level integrator (docs/frame-integrators.md): the pixel pass renders each
/// pixel of the rectangle from its own samples (strategies t >= 2); the light-tracing pass
/// traces every light path of the whole image (t = 1) and keeps the splats inside it.
class BdptIntegrator final : public Integrator {
 public:
  explicit BdptIntegrator(const RenderContext& ctx) : Integrator(ctx), tracer_(ctx_) {
    if (rendersInPasses(ctx_.settings))
      throw Error(
          "bdpt: --noise-threshold and --time-limit are not supported (every pixel takes "
          "--spp samples: the light-tracing pass is shared by all of them)");
    tracer_.setStrategies(strategiesOf(ctx_.settings.getString("bdpt-strategy")));
  }
  Color Li(const Ray&, Sampler&, RayStats&, PrimaryHit*) const override {
    throw Error(
        "bdpt renders whole frames (its light-tracing strategies splat onto any pixel); it "
        "cannot trace single camera rays (e.g. as adaptive's --inner)");
  }
  bool rendersFrames() const override { return true; }
  FrameResult renderFrame(const FrameTask& task, std::span<FramePixel> pixels) const override;

 private:
  void pixelPass(const FrameTask& task, std::span<FramePixel> pixels,
                 std::vector<RayStats>& rowStats) const;
  /// Adds the light-tracing splats to the pixels; false when stopped.
  bool lightPass(const FrameTask& task, std::span<FramePixel> pixels, RayStats& stats) const;
  BdptTracer tracer_;
};

void BdptIntegrator::pixelPass(const FrameTask& task, std::span<FramePixel> pixels,
                               std::vector<RayStats>& rowStats) const {
  const int spp = sampleCount();
  tbb::parallel_for(0, task.height, [&](int row) {
    if (task.stop && task.stop->load(std::memory_order_relaxed)) return;
    RayStats& stats = rowStats[size_t(row)];
    for (int col = 0; col < task.width; ++col) {
      FramePixel& px = pixels[size_t(row) * size_t(task.width) + size_t(col)];
      const int x = task.x0 + col, y = task.y0 + row;
      // Integrator::accumulate's loop, with the tracer's estimate for Li.
      for (int i = 0; i < spp; ++i) {
        Sampler s = sampler(x, y, i);
        Vec2 offset;
        const Ray ray = cameraRay(x, y, i, s, offset);
        ++stats.cameraRays;
        PrimaryHit seen;
        const Color L = tracer_.cameraEstimate(ray, s, stats, &seen);
        if (i == 0) px.first = seen;
        addSample(px.sums, task.wantsIds ? &px.coverage : nullptr, nullptr, offset, L, seen,
                  nullptr, stats);
      }
      px.samples = uint32_t(spp);
    }
  });
}

bool BdptIntegrator::lightPass(const FrameTask& task, std::span<FramePixel> pixels,
                               RayStats& stats) const {
  // One light path per pixel of the whole image per sample index, as many as camera paths
  // (so that the MIS weights' camera density, over the whole image, counts them alike). Light
  // path j of sample i draws from Sampler(j, i, seed'), whichever region renders it.
  const uint32_t perSample = uint32_t(ctx_.width) * uint32_t(ctx_.height);
  const uint32_t chunksPerSample = (perSample + kChunkPaths - 1) / kChunkPaths;
  const size_t chunks = size_t(chunksPerSample) * size_t(sampleCount());
  std::vector<double> sums(pixels.size() * 3, 0.0);
  std::vector<std::vector<std::pair<uint32_t, Color>>> buffers(kChunksPerBatch);
  std::vector<RayStats> chunkStats(kChunksPerBatch);
  for (size_t first = 0; first < chunks; first += kChunksPerBatch) {
    if (task.stop && task.stop->load(std::memory_order_relaxed)) return false;
    const size_t n = std::min(kChunksPerBatch, chunks - first);
    tbb::parallel_for(size_t(0), n, [&](size_t b) {
      const size_t chunk = first + b;
      const uint32_t sample = uint32_t(chunk / chunksPerSample);
      const uint32_t begin = uint32_t(chunk % chunksPerSample) * kChunkPaths;
      const uint32_t end = std::min(perSample, begin + kChunkPaths);
      auto& out = buffers[b];
      out.clear();
      std::vector<Splat> splats;
      for (uint32_t j = begin; j < end; ++j) {
        Sampler s(j, sample, seed() ^ kLightPassSeed, sequence());
        splats.clear();
        tracer_.lightEstimate(s, chunkStats[b], splats);
        for (const Splat& sp : splats) {
          // Box-filtered: the pixel the point lands in (docs/bdpt.md).
          const int x = int(std::floor(sp.raster.x)) - task.x0;
          const int y = int(std::floor(sp.raster.y)) - task.y0;
          if (x < 0 || y < 0 || x >= task.width || y >= task.height) continue;
          if (!isFinite(sp.L)) {
            chunkStats[b].countNonFinite(sp.L);
            continue;
          }
          out.emplace_back(uint32_t(y) * uint32_t(task.width) + uint32_t(x), sp.L);
        }
      }
    });
    for (size_t b = 0; b < n; ++b) {  // in chunk order: the same sums for any thread count
      for (const auto& [p, L] : buffers[b]) {
        sums[3 * p] += L.x, sums[3 * p + 1] += L.y, sums[3 * p + 2] += L.z;
      }
      stats += chunkStats[b];
      chunkStats[b] = RayStats();
    }
    if (task.onProgress) task.onProgress(0.5 + 0.5 * double(first + n) / double(chunks));
  }
  // Each light path estimates the whole image: the pixel's value is the mean over all of
  // them. Added to the pixel's weighted sums as radiance (sums.rgb / sums.weight).
  const double paths = double(perSample) * double(sampleCount());
  for (size_t p = 0; p < pixels.size(); ++p) {
    PixelSums& ps = pixels[p].sums;
    for (int c = 0; c < 3; ++c) ps.rgb[c] += ps.weight * (sums[3 * p + size_t(c)] / paths);
  }
  return true;
}

FrameResult BdptIntegrator::renderFrame(const FrameTask& task, std::span<FramePixel> pixels) const {
  FrameResult r;
  std::vector<RayStats> rowStats(size_t(task.height));
  pixelPass(task, pixels, rowStats);
  for (const RayStats& s : rowStats) r.rays += s;
  if (task.stop && task.stop->load(std::memory_order_relaxed)) {
    r.stopped = true;
    return r;
  }
  if (task.onProgress) task.onProgress(0.5);
  const BdptStrategies which = strategiesOf(ctx_.settings.getString("bdpt-strategy"));
  if (which == BdptStrategies::kAll || which == BdptStrategies::kT1) {
    if (!lightPass(task, pixels, r.rays)) {
      r.stopped = true;
      return r;
    }
  } else if (task.onProgress) {
    task.onProgress(1.0);
  }
  r.iterations = 1;
  return r;
}

const OptionSpec& pathOption(const std::string& name) {
  for (const OptionSpec& spec : pathOptions())
    if (spec.name == name) return spec;
  throw Error("bdpt: path has no option --" + name);
}

}  // namespace

const std::vector<OptionSpec>& bdptOptions() {
  // The options path shares with bdpt are path's own specs: declared once.
  static const std::vector<OptionSpec> specs = {
      pathOption("max-depth"),
      pathOption("light-sampler"),
      pathOption("triangle-sampling"),
      choiceOption("bdpt-strategy", "all", {"all", "s0", "s1", "t1"},
                   "which strategies bdpt takes: all (MIS-weighted), or one family alone, "
                   "unweighted (a debugging check: each converges to the same image where it "
                   "can sample the light): s0 (camera paths that hit emitters), s1 (next-event "
                   "estimation), t1 (light tracing); emitters seen directly are in each"),
  };
  return specs;
}

std::unique_ptr<Integrator> makeBdpt(const RenderContext& ctx) {
  return std::make_unique<BdptIntegrator>(declaring(ctx, bdptOptions()));
}

}  // namespace tray

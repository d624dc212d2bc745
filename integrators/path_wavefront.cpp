#include "integrators/path_wavefront.h"

#include <algorithm>
#include <vector>

#include "core/camera_culling.h"
#include "core/simd_lanes.h"
#include "integrators/camera_batch.h"
#include "integrators/delta_batch.h"
#include "integrators/glossy_batch.h"
#include "integrators/matte_batch.h"
#include "integrators/path.h"
#include "integrators/path_estimator.h"
#include "integrators/sampler_batch.h"
#include "integrators/surface_batch.h"

namespace tray {
namespace {

/// How many vertices ahead of the one being shaded the wave prefetches texels (docs/textures.md,
/// "Prefetching": 16, 32, 64 and the whole queue at once measured alike on the helmets; a short
/// distance keeps the prefetched lines few, for CPUs with smaller caches).
constexpr size_t kTexelPrefetchAhead = 32;

/// Camera rays made per call of the SIMD kernel (integrators/camera_batch.h).
constexpr size_t kCameraChunk = 256;

/// The paths of one wave, their ray queues (structure of arrays: one array per field, so the
/// accelerator reads rays and writes hits contiguously) and their shadow queue. Reused by a
/// thread from one batch to the next: no allocation once grown.
struct Wave {
  // Per path, in (pixel, sample) order.
  std::vector<PathState> paths;
  std::vector<Sampler> samplers;
  std::vector<PrimaryHit> primary;
  std::vector<Vec2> offsets;                  ///< pixel-sampler offset, for the filter weight
  std::vector<LightPathRadiance> lightPaths;  ///< when light-path AOVs are asked for
  // The queue of live paths and its rays, hits.
  std::vector<uint32_t> live, next;
  std::vector<Ray> rays;
  std::vector<Hit> hits;
  std::vector<uint8_t> found;
  std::vector<SurfacePoint> surfaces;  ///< at the found hits (when SurfaceBatch is useful)
  SurfaceBatch::Scratch surfaceScratch;
  SamplerDrawsAhead draws;  ///< each live path's next two 3D draws (when SIMD is available)
  ShadingLanes matte;       ///< the bounce's matte vertices, for the SIMD matte stage
  ShadingLanes glossy;      ///< the bounce's metal and plastic vertices, for the glossy stage
  ShadingLanes delta;       ///< the bounce's smooth glass vertices, for the delta stage
  // The shadow queue: next-event estimates waiting for their rays (slots kept from one bounce
  // to the next; bounce() says how many are in use).
  std::vector<ShadowQuery> shadows;
  std::vector<uint32_t> shadowPath;
  std::vector<Ray> shadowRays;
  std::vector<uint8_t> blocked;
  // The camera-ray kernel's inputs (a chunk's pixels and sample indices) and results.
  int32_t cameraX[kCameraChunk], cameraY[kCameraChunk];
  uint32_t cameraSample[kCameraChunk];
  CameraRayLanes cameraLanes;

  void clear() { paths.clear(), samplers.clear(), primary.clear(), offsets.clear(); }
  /// A path from its camera ray; `split`: its light-path radiance, or null.
  void addPath(const Ray& ray, int x, int y, LightPathRadiance* split, const Sampler& sampler,
               const Vec2& offset) {
    paths.emplace_back().beginCamera(ray, x, y, split);
    addRestOfPath(sampler, offset);
  }
  /// The rest of a path whose state was just added: its sampler, first hit and offset.
  void addRestOfPath(const Sampler& sampler, const Vec2& offset) {
    samplers.push_back(sampler);
    primary.emplace_back();
    offsets.push_back(offset);
  }
};

/// A pixel whose light-path AOVs are asked for.
bool wantsLightPaths(const PixelTask& t) {
  return t.aovSums && t.aovSums->lightPaths;
}

class PathWavefrontIntegrator final : public Integrator {
 public:
  explicit PathWavefrontIntegrator(const RenderContext& ctx)
      : Integrator(ctx),
        estimator_(ctx_),
        surfaces_(ctx_.scene),
        drawsAhead_(hasSimdTarget()),
        textured_(estimator_.textured()),
        matte_(estimator_.lights()),
        glossy_(matte_),
        cameraBatch_(CameraRayBatch::make(ctx_.camera, pixelSampler(), seed(), sequence(), moving(),
                                          ctx_.width)) {}

  /// A 16 x 16 tile (the renderer's default) at once.
  int pixelBatch() const override { return 256; }

  uint32_t accumulate(int x, int y, int begin, int end, PixelSums& sums, PrimaryHit& first,
                      RayStats& stats, IdCoverage* coverage, AovSums* aovSums) const override {
    PixelTask task;
    task.x = x, task.y = y, task.sums = sums, task.first = first, task.coverage = coverage;
    task.aovSums = aovSums;
    accumulatePixels({&task, 1}, begin, end, stats, nullptr);
    sums = task.sums, first = task.first;
    return task.samples;
  }
  bool splitsLightPaths() const override { return true; }

  void accumulatePixels(std::span<PixelTask> tasks, int begin, int end, RayStats& stats,
                        const std::atomic<bool>* stop) const override;
  /// The wave's paths g0 <= g < g1 of the batch (sample begin + g % n of tasks[g / n]'s pixel),
  /// from the camera-ray kernel: what accumulatePixels' scalar loop makes, bit for bit.
  void beginPathsInSimd(Wave& w, std::span<const PixelTask> tasks, int begin, size_t n, size_t g0,
                        size_t g1) const;

  /// One path on its own (adaptive's inner integrator): nothing to batch it with, so the
  /// scalar driver's loop (PathEstimator::tracePath), which `path-scalar` runs too: the same
  /// pixels under `adaptive --inner path` as under `--inner path-scalar`. (A wave of one did
  /// not keep a PrimaryHit the caller had filled, and was 30% slower.)
  Color Li(const Ray& ray, Sampler& sampler, RayStats& stats, PrimaryHit* primary) const override {
    return estimator_.tracePath(ctx_.accel, ray, sampler, stats, primary, -1, -1);
  }

 private:
  static Wave& scratch() {
    static thread_local Wave wave;
    return wave;
  }
  void trace(Wave& w, RayStats& stats) const;
  /// `cameraRays`: the queue holds the wave's camera rays (its first bounce).
  void bounce(Wave& w, RayStats& stats, bool cameraRays) const;
  PathEstimator estimator_;
  SurfaceBatch surfaces_;
  bool drawsAhead_;     ///< each bounce makes its paths' 3D draws in SIMD (SamplerBatch)
  bool textured_;       ///< some material samples a texture: prefetch the queue's texels
  MatteBatch matte_;    ///< matte vertices' light and BSDF samples in SIMD (when useful)
  GlossyBatch glossy_;  ///< the same for metal and plastic vertices (when matte_ is useful)
  DeltaBatch delta_;    ///< smooth glass vertices' BSDF samples in SIMD (when useful)
  std::optional<CameraRayBatch> cameraBatch_;  ///< nothing: cameras the kernel does not cover
};

void PathWavefrontIntegrator::accumulatePixels(std::span<PixelTask> tasks, int begin, int end,
                                               RayStats& stats,
                                               const std::atomic<bool>* stop) const {
  end = std::min(end, sampleCount());
  const size_t n = size_t(std::max(0, end - begin));
  for (PixelTask& t : tasks) t.samples = uint32_t(n), t.finished = n == 0;  // none: done
  const size_t total = tasks.size() * n;
  Wave& w = scratch();
  const bool anySplit = std::any_of(tasks.begin(), tasks.end(), wantsLightPaths);
  // Paths in (pixel, sample) order, cut into waves: each pixel's samples are added to its sums
  // in sample order, as accumulate() does, so the sums are the same bits.
  for (size_t g0 = 0; g0 < total; g0 += kPathWaveSize) {
    // A stop between waves: the pixels whose samples all came before are finished.
    if (stop && stop->load(std::memory_order_relaxed)) break;
    const size_t g1 = std::min(total, g0 + kPathWaveSize);
    w.clear();
    // Sized before the paths point into it; zero, as accumulate() clears a sample's split.
    w.lightPaths.assign(anySplit ? g1 - g0 : 0, LightPathRadiance{});
    if (cameraBatch_) {
      beginPathsInSimd(w, tasks, begin, n, g0, g1);
      stats.cameraRays += g1 - g0;
    } else {
      for (size_t g = g0; g < g1; ++g) {
        const PixelTask& t = tasks[g / n];
        const int i = begin + int(g % n);
        Sampler s = sampler(t.x, t.y, i);
        Vec2 offset;
        const Ray ray = cameraRay(t.x, t.y, i, s, offset);
        ++stats.cameraRays;
        w.addPath(ray, t.x, t.y, wantsLightPaths(t) ? &w.lightPaths[g - g0] : nullptr, s, offset);
      }
    }
    trace(w, stats);
    for (size_t g = g0; g < g1; ++g) {
      PixelTask& t = tasks[g / n];
      const size_t k = g - g0;
      if (g % n == 0) t.first = w.primary[k];
      addSample(t.sums, t.coverage, t.aovSums, w.offsets[k], PathEstimator::result(w.paths[k]),
                w.primary[k], wantsLightPaths(t) ? &w.lightPaths[k] : nullptr, stats);
      if (g % n == n - 1) t.finished = true;
    }
  }
}

void PathWavefrontIntegrator::beginPathsInSimd(Wave& w, std::span<const PixelTask> tasks, int begin,
                                               size_t n, size_t g0, size_t g1) const {
  // In chunks whose kernel inputs and results stay in the L1 cache; pixel and sample counted
  // along (no division per path).
  size_t task = g0 / n, sample = g0 % n;
  for (size_t c0 = g0; c0 < g1; c0 += kCameraChunk) {
    const size_t c1 = std::min(g1, c0 + kCameraChunk);
    const size_t chunkTask = task, chunkSample = sample;
    for (size_t k = 0; k < c1 - c0; ++k) {
      w.cameraX[k] = tasks[task].x, w.cameraY[k] = tasks[task].y;
      w.cameraSample[k] = uint32_t(begin + int(sample));
      if (++sample == n) sample = 0, ++task;
    }
    cameraBatch_->generate(c1 - c0, w.cameraX, w.cameraY, w.cameraSample, w.cameraLanes);
    task = chunkTask, sample = chunkSample;
    for (size_t k = 0; k < c1 - c0; ++k) {
      const PixelTask& t = tasks[task];
      // The camera ray straight into the path's state (no Ray temporary:
      // integrators/camera_batch.h).
      PathState& st = w.paths.emplace_back();
      cameraBatch_->setRay(w.cameraLanes, k, st.ray);
      st.beginCamera(t.x, t.y, wantsLightPaths(t) ? &w.lightPaths[c0 + k - g0] : nullptr);
      w.addRestOfPath(cameraBatch_->sampler(w.cameraLanes, k),
                      CameraRayBatch::offset(w.cameraLanes, k));
      if (++sample == n) sample = 0, ++task;
    }
  }
}

void PathWavefrontIntegrator::trace(Wave& w, RayStats& stats) const {
  if (estimator_.maxDepth() == 0) return;  // nothing is traced: black, nothing hit
  w.live.resize(w.paths.size());
  for (size_t k = 0; k < w.live.size(); ++k) w.live[k] = uint32_t(k);
  // The first segments are the camera rays, in pixel order: coherent.
  for (bool first = true; !w.live.empty(); first = false) bounce(w, stats, first);
}

/// One segment of every live path: trace the queue, shade each hit (emission, light sample,
/// BSDF sample), then trace the shadow queue and add the unoccluded estimates.
void PathWavefrontIntegrator::bounce(Wave& w, RayStats& stats, bool cameraRays) const {
  const size_t count = w.live.size();
  w.rays.resize(count), w.hits.resize(count), w.found.resize(count);
  for (size_t j = 0; j < count; ++j) w.rays[j] = w.paths[w.live[j]].ray;
  if (cameraRays) {
    ctx_.accel.intersectCoherentBatch(w.rays, w.hits, w.found);
    // Single-sided back faces are culled for the camera (core/camera_culling.h): the rare ray
    // that found one is traced on alone from there, as path-scalar traces it.
    for (size_t j = 0; j < count; ++j)
      if (w.found[j]) w.found[j] = passCulledFaces(ctx_.accel, ctx_.scene, w.rays[j], w.hits[j]);
  } else
    ctx_.accel.intersectBatch(w.rays, w.hits, w.found);
  // The hits' surfaces in SIMD (integrators/surface_batch.h).
  const bool surfacesKnown = surfaces_.useful();
  // Texels are prefetched from the surfaces' uvs (docs/textures.md, "Prefetching").
  const bool prefetching = textured_ && surfacesKnown;
  if (surfacesKnown) {
    w.surfaces.resize(count);
    surfaces_.compute(w.rays, w.hits, w.found, w.surfaces, w.surfaceScratch);
    // The first vertices' texels asked for now, the others' kTexelPrefetchAhead vertices ahead
    // in the loop below: their cache misses overlap other work instead of stalling each
    // vertex's material lookups in turn.
    if (prefetching)
      for (size_t j = 0; j < std::min(count, kTexelPrefetchAhead); ++j)
        if (w.found[j]) estimator_.prefetchTextures(w.surfaces[j]);
  }
  // The vertices' light-sample and BSDF-sample draws, for every live path at once (a path that
  // missed, or crosses a null interface, leaves them unused: its sampler does not advance).
  if (drawsAhead_)
    SamplerBatch::drawTwo3D(sequence(), w.samplers.data(), w.live.data(), count, w.draws);

  // Matte, glossy and smooth glass vertices wait in w.matte, w.glossy and w.delta for the SIMD
  // stages (integrators/matte_batch.h, glossy_batch.h, delta_batch.h); the first two sample the
  // same lights. They need the draws made ahead.
  const bool deferring = drawsAhead_ && delta_.useful();
  if (deferring) w.matte.reset(count), w.glossy.reset(count), w.delta.reset(count);
  const ShadingDeferral deferral{matte_, w.matte, w.glossy, w.delta, matte_.useful()};

  w.next.clear();
  // step() writes a next-event estimate straight into the queue's next slot, setting what
  // resolveShadow reads (as the scalar path reuses one query): no default-initialised query
  // per vertex, and no copy of one just written (a store-forwarding stall, core/ray.h).
  if (w.shadows.size() < count) w.shadows.resize(count), w.shadowPath.resize(count);
  size_t shadowCount = 0;
  for (size_t j = 0; j < count; ++j) {
    const size_t ahead = j + kTexelPrefetchAhead;
    if (prefetching && ahead < count && w.found[ahead])
      estimator_.prefetchTextures(w.surfaces[ahead]);
    const uint32_t k = w.live[j];
    bool wantsShadow;
    const WavefrontVertex made{
        surfacesKnown ? &w.surfaces[j] : nullptr,
        drawsAhead_ ? DrawsAhead{&w.draws.first[j], &w.draws.second[j]} : DrawsAhead{},
        deferring ? &deferral : nullptr, k};
    const PathStep step =
        estimator_.step(w.paths[k], w.samplers[k], w.found[j] ? &w.hits[j] : nullptr,
                        w.shadows[shadowCount], wantsShadow, stats, &w.primary[k], made);
    if (wantsShadow) w.shadowPath[shadowCount++] = k;
    if (step == PathStep::kContinue) w.next.push_back(k);
  }
  // The stages' results become shadow queries and next segments, path by path (the delta
  // stage's vertices sampled no light: no shadow query).
  const auto finish = [&](ShadingLanes& lanes, bool delta) {
    stats.simdVertices += lanes.count;
    for (size_t q = 0; q < lanes.count; ++q) {
      const uint32_t k = lanes.path[q];
      bool wantsShadow = false;
      const PathStep step =
          delta ? estimator_.finishDelta(w.paths[k], w.samplers[k], lanes, q, stats)
                : estimator_.finishDeferred(w.paths[k], w.samplers[k], lanes, q,
                                            w.shadows[shadowCount], wantsShadow, stats);
      if (wantsShadow) w.shadowPath[shadowCount++] = k;
      if (step == PathStep::kContinue) w.next.push_back(k);
    }
  };
  if (deferring && w.matte.count > 0) matte_.compute(w.matte), finish(w.matte, false);
  if (deferring && w.glossy.count > 0) glossy_.compute(w.glossy), finish(w.glossy, false);
  if (deferring && w.delta.count > 0) delta_.compute(w.delta), finish(w.delta, true);

  w.shadowRays.resize(shadowCount), w.blocked.resize(shadowCount);
  for (size_t q = 0; q < shadowCount; ++q) w.shadowRays[q] = w.shadows[q].ray;
  ctx_.accel.occludedBatch(w.shadowRays, w.blocked);
  for (size_t q = 0; q < shadowCount; ++q)
    estimator_.resolveShadow(w.paths[w.shadowPath[q]], w.shadows[q], w.blocked[q]);
  std::swap(w.live, w.next);
}

}  // namespace

std::unique_ptr<Integrator> makePathWavefront(const RenderContext& ctx) {
  return std::make_unique<PathWavefrontIntegrator>(declaring(ctx, pathOptions()));
}

}  // namespace tray

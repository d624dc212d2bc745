#include "core/integrator.h"

#include <algorithm>
#include <cmath>

#include "core/camera_lanes.h"
#include "core/error.h"
#include "core/filter.h"
#include "core/motion.h"
#include "core/pixel_sampler.h"

namespace tray {
namespace {

/// The settings' pixel sampler over a filter support of the given radius ("auto" depends on
/// whether the random sequence stratifies).
PixelSampler pixelSamplerOf(const RenderSettings& s, Sampler::Sequence sequence, float radius) {
  const bool stratified = sequence == Sampler::Sequence::kSobol;
  const int spp = s.getInt("spp");
  return PixelSampler(
      PixelSampler::parse(s.getString("pixel-sampler"), spp, stratified, rendersInPasses(s)), spp,
      radius);
}

}  // namespace

Integrator::Integrator(const RenderContext& ctx)
    : ctx_(ctx),
      filter_(Filter::make(ctx.settings.getString("filter"))),
      sequence_(Sampler::parse(ctx.settings.getString("sampler"))),
      pixelSampler_(pixelSamplerOf(ctx.settings, sequence_, filter_.radius())),
      seed_(uint64_t(ctx.settings.getInt64("seed"))),
      transparent_(ctx.settings.getBool("transparent") || ctx.scene.environment.transparent),
      moving_(ctx.scene.moving() || !ctx.camera.desc().motion.empty()),
      cameraMotion_(ctx.camera.desc().motion),
      cameraFrameInverse_(ctx.camera.desc().toWorld.inv) {}

void Integrator::moveWithCamera(Ray& ray) const {
  // From the camera at the frame's pose (where generateRay put the ray) to the camera at the
  // ray's time: the ray keeps its place in camera space.
  Transform move;
  move.m = interpolateSteps(cameraMotion_, ray.time) * cameraFrameInverse_;  // point() reads m
  ray.o = move.point(ray.o);
  ray.d = move.vector(ray.d);
}

Color Integrator::cameraLi(const Ray& ray, Sampler& sampler, RayStats& stats,
                           PrimaryHit* primary) const {
  const Color L = Li(ray, sampler, stats, primary);
  // The environment still lit every surface the ray met (reflections, light); only what the
  // camera sees of it directly is left out, as a compositor's "over" expects (Porter & Duff
  // 1984: premultiplied colour, alpha = coverage).
  if (!(transparent_ && !primary->hit)) return L;
  if (primary->lightPaths) primary->lightPaths->clear();
  return Color(0.0f);
}

RenderContext declaring(const RenderContext& ctx, const std::vector<OptionSpec>& specs) {
  RenderContext bound = ctx;
  bound.settings.declare(specs);
  bound.settings.validate();
  return bound;
}

std::optional<int> Integrator::samplesPerPixel() const {
  return pixelSampler_.count();
}

Sampler Integrator::sampler(int x, int y, int i) const {
  const uint32_t pixelIndex = uint32_t(y) * uint32_t(ctx_.width) + uint32_t(x);
  return Sampler(pixelIndex, uint32_t(i), seed_, sequence_);
}

Ray Integrator::cameraRay(int x, int y, int i, Sampler& sampler, Vec2& offset) const {
  offset = pixelSampler_.offset(i, sampler.next2D());
  const float rx = rasterCoordinate(float(x), offset.x), ry = rasterCoordinate(float(y), offset.y);
  // A thin lens takes the next 2D point of the camera-ray group; a pinhole draws nothing
  // more, so its images keep every bit.
  Ray ray = ctx_.camera.hasLens() ? ctx_.camera.generateLensRay(rx, ry, sampler.next2D())
                                  : ctx_.camera.generateRay(rx, ry);
  setShutterTime(ray, sampler);  // static objects keep every bit (docs/scene-format.md)
  return ray;
}

void Integrator::addSample(PixelSums& sums, IdCoverage* coverage, AovSums* aovSums,
                           const Vec2& offset, Color L, const PrimaryHit& seen,
                           const LightPathRadiance* paths, RayStats& stats) const {
  // The environment still lit every surface the ray met (reflections, light); only what the
  // camera sees of it directly is left out (cameraLi), from the light-path split too.
  if (transparent_ && !seen.hit) {
    L = Color(0.0f);
    paths = nullptr;
  }
  if (!isFinite(L)) {
    stats.countNonFinite(L);
    L = Color(0.0f);
    paths = nullptr;  // a split of zeros adds nothing: its sums keep every bit
  }
  const double w = filter_.evaluate(offset);
  sums.rgb[0] += w * L.x, sums.rgb[1] += w * L.y, sums.rgb[2] += w * L.z;
  sums.alpha += seen.hit ? w : 0.0;
  sums.weight += w;
  if (coverage) coverage->add(seen.hit ? seen.objectId : -1, seen.hit ? seen.materialId : -1, w);
  if (aovSums) {
    aovSums->addWeight(w);
    if (paths && aovSums->lightPaths) aovSums->addLightPaths(*paths, w);
    if (aovSums->surface) aovSums->addSurface(seen.hit, seen.albedo, seen.normal, seen.depth, w);
  }
}

// Flattened: the sampler, camera ray and addSample pieces inline here as in one function
// (measured: their calls cost the scalar path about 0.5% of its instructions).
[[gnu::flatten]] uint32_t Integrator::accumulate(int x, int y, int begin, int end, PixelSums& sums,
                                                 PrimaryHit& first, RayStats& stats,
                                                 IdCoverage* coverage, AovSums* aovSums) const {
  // Filter-weighted sums, normalised by the weight sum at the end (pbrt-v4 8.8's weighted
  // estimator): each pixel owns its samples, so tiles never share film writes. Doubles keep the
  // mean accurate at very high sample counts and let sums of sample ranges be combined.
  end = std::min(end, pixelSampler_.count());
  LightPathRadiance paths;
  LightPathRadiance* splitInto = aovSums && aovSums->lightPaths ? &paths : nullptr;
  for (int i = begin; i < end; ++i) {
    Sampler s = sampler(x, y, i);
    Vec2 d;
    const Ray ray = cameraRay(x, y, i, s, d);
    ++stats.cameraRays;
    PrimaryHit primary;
    PrimaryHit& seen = i == begin ? first : primary;
    if (splitInto) paths.clear();
    seen.lightPaths = splitInto;
    const Color L = Li(ray, s, stats, &seen);
    seen.lightPaths = nullptr;
    addSample(sums, coverage, aovSums, d, L, seen, splitInto, stats);
  }
  return uint32_t(std::max(0, end - begin));
}

void Integrator::accumulatePixels(std::span<PixelTask> tasks, int begin, int end, RayStats& stats,
                                  const std::atomic<bool>* stop) const {
  for (PixelTask& t : tasks) {
    if (stop && stop->load(std::memory_order_relaxed)) return;
    t.samples = accumulate(t.x, t.y, begin, end, t.sums, t.first, stats, t.coverage, t.aovSums);
    t.finished = true;
  }
}

PixelValue Integrator::renderPixel(int x, int y, RayStats& stats, IdCoverage* coverage) const {
  PixelSums sums;
  PixelValue out;
  out.samples = accumulate(x, y, 0, pixelSampler_.count(), sums, out.primary, stats, coverage);
  out.radiance = sums.radiance();
  out.alpha = sums.coverage();
  return out;
}

FrameResult Integrator::renderFrame(const FrameTask&, std::span<FramePixel>) const {
  throw Error("this integrator renders pixels, not whole frames", Error::Kind::kRender);
}

}  // namespace tray

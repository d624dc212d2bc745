#include "integrators/integrator.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/filter.h"
#include "core/pixel_sampler.h"

namespace tray {

PixelValue Integrator::renderPixel(int x, int y, RayStats& stats, IdCoverage* coverage) const {
  const RenderSettings& s = ctx_.settings;
  const Filter filter = Filter::make(s.filter);
  const PixelSampler pixelSampler(PixelSampler::parse(s.pixelSampler, s.spp), s.spp, filter.radius());
  const uint32_t pixelIndex = uint32_t(y) * uint32_t(ctx_.width) + uint32_t(x);
  const float cx = x + 0.5f, cy = y + 0.5f;
  // Filter-weighted average, normalised by the weight sum (pbrt-v4 8.8's weighted estimator):
  // each pixel owns its samples, so tiles never share film writes. Doubles keep the mean
  // accurate at very high sample counts.
  double sum[3] = {0, 0, 0}, alpha = 0, weights = 0;
  PixelValue out;
  const int n = pixelSampler.count();
  for (int i = 0; i < n; ++i) {
    Sampler sampler(pixelIndex, uint32_t(i), s.seed);
    const Vec2 d = pixelSampler.offset(i, sampler.next2D());
    Ray ray = ctx_.camera.generateRay(cx + d.x, cy + d.y);
    ++stats.cameraRays;
    PrimaryHit primary;
    PrimaryHit& seen = i == 0 ? out.primary : primary;
    Color L = Li(ray, sampler, stats, &seen);
    if (!isFinite(L)) {
      ++stats.nanSamples;
      L = Color(0.0f);
    }
    const double w = filter.evaluate(d);
    sum[0] += w * L.x, sum[1] += w * L.y, sum[2] += w * L.z;
    alpha += seen.hit ? w : 0.0;
    weights += w;
    if (coverage) coverage->add(seen.hit ? seen.objectId : -1, seen.hit ? seen.materialId : -1, w);
  }
  if (weights != 0) {
    out.radiance = Color(float(sum[0] / weights), float(sum[1] / weights), float(sum[2] / weights));
    out.alpha = std::clamp(float(alpha / weights), 0.0f, 1.0f);  // Mitchell's lobes can overshoot
  }
  out.samples = uint32_t(n);
  return out;
}

std::unique_ptr<Integrator> makeIntegrator(const RenderContext& ctx, const std::string& name) {
  const std::string& wanted = name.empty() ? ctx.settings.integrator : name;
  for (const auto& e : integratorRegistry())
    if (wanted == e.name) return e.create(ctx);
  std::string known;
  for (const auto& e : integratorRegistry()) known += std::string(known.empty() ? "" : ", ") + e.name;
  throw Error("unknown integrator '" + wanted + "' (known: " + known + ")");
}

}  // namespace tray

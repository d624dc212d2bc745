#include "integrators/integrator.h"

#include <cmath>

#include "core/error.h"

namespace tray {

PixelValue Integrator::renderPixel(int x, int y, RayStats& stats) const {
  const RenderSettings& s = ctx_.settings;
  const int spp = std::max(1, s.spp);
  const uint32_t pixelIndex = uint32_t(y) * uint32_t(ctx_.width) + uint32_t(x);
  // Stratified jitter on the largest square grid that fits spp; the rest uniformly jittered.
  // One sample sits at the pixel centre (the seed's ray casting) unless jitter is asked for.
  const int strata = int(std::sqrt(double(spp)));
  const bool center = s.pixelSampler == "center" || (s.pixelSampler == "auto" && spp == 1);
  double sum[3] = {0, 0, 0}, alpha = 0;
  PixelValue out;
  for (int i = 0; i < spp; ++i) {
    Sampler sampler(pixelIndex, uint32_t(i), s.seed);
    Vec2 u = sampler.next2D();
    float px, py;
    if (center) {
      px = x + 0.5f, py = y + 0.5f;
    } else if (i < strata * strata) {
      px = x + (float(i % strata) + u.x) / float(strata);
      py = y + (float(i / strata) + u.y) / float(strata);
    } else {
      px = x + u.x, py = y + u.y;
    }
    Ray ray = ctx_.camera.generateRay(px, py);
    ++stats.cameraRays;
    PrimaryHit primary;
    Color L = Li(ray, sampler, stats, i == 0 ? &out.primary : &primary);
    if (!isFinite(L)) {
      ++stats.nanSamples;
      L = Color(0.0f);
    }
    // Double accumulation keeps the mean accurate at very high sample counts.
    sum[0] += L.x, sum[1] += L.y, sum[2] += L.z;
    alpha += (i == 0 ? out.primary.hit : primary.hit) ? 1.0 : 0.0;
  }
  out.radiance = Color(float(sum[0] / spp), float(sum[1] / spp), float(sum[2] / spp));
  out.alpha = float(alpha / spp);
  out.samples = uint32_t(spp);
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

#include "integrators/sppm.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "integrators/sppm_integrator.h"

namespace tray {

SppmIntegrator::SppmIntegrator(const RenderContext& ctx)
    : Integrator(ctx),
      maxDepth_(int(ctx.settings.getInt("max-depth"))),
      iterations_(int(ctx.settings.getInt("spp"))),
      photons_(uint32_t(ctx.settings.getInt("photons"))),
      alpha_(ctx.settings.getFloat("sppm-alpha")),
      radius_(ctx.settings.getFloat("sppm-radius")),
      // Photons draw from samplers of their own, apart from every pixel's (Sampler(i, k, seed)).
      photonSeed_(uint64_t(ctx.settings.getInt("seed")) ^ 0x5350504d50686f74ull),
      vertices_(ctx_, iterations_),
      lights_(ctx.scene),
      emitter_(lights_) {}

Color SppmIntegrator::Li(const Ray&, Sampler&, RayStats&, PrimaryHit*) const {
  throw Error(
      "--integrator sppm renders whole frames: it cannot be the --inner integrator of adaptive");
}

float SppmIntegrator::initialRadius(int x, int y, float along) const {
  if (radius_ > 0) return radius_;
  // The distance between the rays through the centres of two neighbouring pixels, `along` the
  // path from the camera: a pinhole's angle per pixel times the distance, an orthographic
  // camera's pixel width. A chain of mirrors keeps about the footprint of its total length.
  const float cx = float(x) + 0.5f, cy = float(y) + 0.5f;
  const Ray a = ctx_.camera.generateRay(cx, cy), b = ctx_.camera.generateRay(cx + 1, cy);
  const float spread =
      length((b.o + b.d * (along / length(b.d))) - (a.o + a.d * (along / length(a.d))));
  return kFootprints * std::max(spread, 1e-6f * std::max(1.0f, along));
}

FrameResult SppmIntegrator::renderFrame(const FrameTask& task, std::span<FramePixel> pixels) const {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const size_t n = pixels.size();
  std::vector<SppmPixel> stats(n);
  std::vector<VisiblePoint> vps(n);
  std::vector<Color> phi(n);
  std::vector<uint32_t> m(n);
  FrameResult result;
  for (int k = 0; k < iterations_; ++k) {
    if (task.stop && task.stop->load(std::memory_order_relaxed)) {
      result.stopped = true;
      break;
    }
    cameraPass(task, k, vps, stats, pixels, result.rays);
    photonPass(k, vps, stats, phi, m, result.rays);
    // Hachisuka & Jensen 2009, eqs. 9-10 (pbrt-v3 16.2.5): keep the fraction alpha of the new
    // photons, shrink the radius to match and scale the gathered flux with the disc's area.
    tbb::parallel_for(size_t(0), n, [&](size_t p) {
      SppmPixel& s = stats[p];
      if (m[p] > 0) {
        const float nNew = s.n + alpha_ * float(m[p]);
        const float rNew = s.radius * std::sqrt(nNew / (s.n + float(m[p])));
        const VisiblePoint& vp = vps[p];
        s.tau = (s.tau + vp.beta * phi[p]) * ((rNew * rNew) / (s.radius * s.radius));
        s.n = nNew;
        s.radius = rNew;
      }
      vps[p].bsdf.reset();
    });
    ++result.iterations;
    if (task.onProgress) task.onProgress(double(k + 1) / iterations_);
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (task.timeLimit > 0 && elapsed >= task.timeLimit && k + 1 < iterations_) {
      result.timeLimitReached = true;
      break;
    }
  }
  // The pixel's estimate (Hachisuka & Jensen 2009, eq. 11 with pbrt-v3's direct term):
  // L = Ld / K + tau / (K Np pi r^2), K iterations of Np photons each.
  const double iterations = std::max(1, result.iterations);
  const double photons = iterations * double(photons_);
  tbb::parallel_for(size_t(0), n, [&](size_t p) {
    const SppmPixel& s = stats[p];
    const double area = s.radius > 0 ? kPi * double(s.radius) * s.radius : 1.0;
    PixelSums& sums = pixels[p].sums;
    for (int c = 0; c < 3; ++c) sums.rgb[c] = s.ld[c] / iterations + s.tau[c] / (photons * area);
    sums.alpha = double(s.hits) / iterations;
    sums.weight = 1;
  });
  return result;
}

const std::vector<OptionSpec>& sppmOptions() {
  static const std::vector<OptionSpec> specs = {
      intOption("max-depth", 8, 1, 1000,
                "maximum path length in segments, camera and photon segments together (path's "
                "meaning: 1 emitters seen directly, 2 direct light, 3 one indirect bounce)"),
      intOption("photons", 100000, 1, 1 << 28, "photons traced from the lights per iteration"),
      floatOption("sppm-radius", 0.0f, 0.0f, std::numeric_limits<float>::infinity(),
                  "initial photon gathering radius in scene units (0: two pixel footprints at "
                  "each pixel's first visible point)"),
      floatOption("sppm-alpha", 2.0f / 3.0f, 0.01f, 1.0f,
                  "fraction of each iteration's photons kept as the radius shrinks "
                  "(Hachisuka & Jensen's alpha; 1 keeps the radius)"),
  };
  return specs;
}

std::unique_ptr<Integrator> makeSppm(const RenderContext& ctx) {
  return std::make_unique<SppmIntegrator>(declaring(ctx, sppmOptions()));
}

}  // namespace tray

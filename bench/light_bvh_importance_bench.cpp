// The light BVH's importance (core/light_bounds.cpp, LightBounds::importance) measured where it
// matters: RMSE at equal CPU time (1 render thread, CPU seconds) against a converged reference,
// on the shared Cornell box and on the many-light scenes of tests/light_scenes.h, and the cost
// of one choice (LightSet::choose, the BVH walk) at random receivers. RMSE^2 x seconds is
// constant for an unbiased estimator: its inverse is the figure of merit (higher is better).
// Unbiasedness: the reference's mean against a render that chooses lights by power alone.
// Usage: light_bvh_importance_bench [--size WxH] [--ref-spp N] [--spp N] [--ref-threads N]
//        [--seeds N] [--cache DIR] [--only cornell|many|quads] [--no-bias-check]
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <random>

#include "bench/cpu_time.h"
#include "bench/image_error.h"
#include "bench/timed_render.h"
#include "gltf/gltf_loader.h"
#include "lights/light_set.h"
#include "tests/light_scenes.h"

using namespace tray;

namespace {

struct Setup {
  int width = 128, height = 96, refSpp = 4096, spp = 64, refThreads = 2;
  int seeds = 4;
  bool checkBias = true;
  std::string cacheDir, only;
};

TimedFilm render(const Scene& scene, const Setup& setup, int spp, int seed, int threads,
                 const char* chooser = "bvh") {
  RenderSettings settings;
  settings.set("integrator", "path");
  settings.set("spp", spp);
  settings.set("seed", seed);
  settings.set("light-sampler", std::string(chooser));
  return timedRender(scene, setup.width, setup.height, settings, threads);
}

/// Nanoseconds per LightSet::choose at receivers spread over the scene's box, random normals.
double chooseNanoseconds(const Scene& scene) {
  const LightSet lights(scene, LightSamplerKind::kBvh);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const Bounds3 b = scene.bounds();
  std::vector<LightSampleContext> ctxs;
  for (int i = 0; i < 4096; ++i) {
    const Vec3 p = b.lo + Vec3(u01(rng), u01(rng), u01(rng)) * b.diagonal();
    const float z = 2 * u01(rng) - 1, phi = 2 * kPi * u01(rng), r = std::sqrt(1 - z * z);
    ctxs.push_back({p, Vec3(r * std::cos(phi), z, r * std::sin(phi)), false, false});
  }
  const int rounds = 100;
  double sink = 0;
  const double t0 = cpuSeconds();
  for (int k = 0; k < rounds; ++k)
    for (size_t i = 0; i < ctxs.size(); ++i) {
      float pmf;
      sink += lights.choose(ctxs[i], float(i) / float(ctxs.size()), pmf) + pmf;
    }
  const double t = cpuSeconds() - t0;
  if (sink == 0.5) std::printf(" ");  // keep the loop
  return 1e9 * t / (double(rounds) * double(ctxs.size()));
}

/// The reference, kept in `cache` (raw floats) when it names a file: read when it exists.
Film reference(const Scene& scene, const Setup& setup, const std::string& cache) {
  const size_t n = size_t(setup.width) * size_t(setup.height) * 3;
  std::vector<float> rgb(n);
  if (FILE* f = cache.empty() ? nullptr : std::fopen(cache.c_str(), "rb")) {
    const size_t got = std::fread(rgb.data(), sizeof(float), n, f);
    std::fclose(f);
    if (got == n) {
      Film film(setup.width, setup.height);
      for (int y = 0; y < setup.height; ++y)
        for (int x = 0; x < setup.width; ++x)
          for (int c = 0; c < 3; ++c)
            film.pixel(Film::kBeauty, x, y)[c] =
                rgb[(size_t(y) * size_t(setup.width) + size_t(x)) * 3 + size_t(c)];
      return film;
    }
  }
  Film film = render(scene, setup, setup.refSpp, 99, setup.refThreads).film;
  if (FILE* f = cache.empty() ? nullptr : std::fopen(cache.c_str(), "wb")) {
    for (int y = 0; y < setup.height; ++y)
      for (int x = 0; x < setup.width; ++x)
        for (int c = 0; c < 3; ++c)
          rgb[(size_t(y) * size_t(setup.width) + size_t(x)) * 3 + size_t(c)] =
              film.pixel(Film::kBeauty, x, y)[c];
    std::fwrite(rgb.data(), sizeof(float), n, f);
    std::fclose(f);
  }
  return film;
}

void measure(const char* name, const std::string& key, const Scene& scene, const Setup& setup) {
  if (!setup.only.empty() && setup.only != key) return;
  std::printf("\n%s (%dx%d, reference %d spp)\n", name, setup.width, setup.height, setup.refSpp);
  const std::string cache = setup.cacheDir.empty()
                                ? std::string()
                                : setup.cacheDir + "/" + key + "-" + std::to_string(setup.width) +
                                      "x" + std::to_string(setup.height) + "-" +
                                      std::to_string(setup.refSpp) + ".raw";
  const Film reference = ::reference(scene, setup, cache);
  std::printf(
      "| spp | RMSE (%d seeds) | CPU s | 1/(RMSE^2 s) | choose ns |\n|---|---|---|---|---|\n",
      setup.seeds);
  // Over `seeds` renders: the mean of their squared errors and of their times (one seed's
  // RMSE at 64 spp among hundreds of small lamps depends on a few fireflies).
  double mse = 0, seconds = 0;
  for (int seed = 1; seed <= setup.seeds; ++seed) {
    const TimedFilm r = render(scene, setup, setup.spp, seed, 1);
    const double e = compareBeauty(r.film, reference).rmse;
    mse += e * e / setup.seeds;
    seconds += r.seconds / setup.seeds;
  }
  std::printf("| %d | %.5f | %.3f | %.1f | %.1f |\n", setup.spp, std::sqrt(mse), seconds,
              1.0 / (mse * seconds), chooseNanoseconds(scene));
  // Unbiased: the channel means of the BVH's reference against a render that chooses by power
  // alone (pbrt-v4's PowerLightSampler, no importance at all), a quarter of its samples.
  if (!setup.checkBias) return;
  const Film power = render(scene, setup, setup.refSpp / 4, 7, setup.refThreads, "power").film;
  // Per channel: the mean of (reference - power) over pixels and its standard error (the
  // pixels' spread over sqrt(count)); unbiased when within a few standard errors.
  const char* names[3] = {"R", "G", "B"};
  std::printf(
      "reference (bvh) - power render (%d spp), per channel mean (standard error), "
      "relative to the mean:",
      setup.refSpp / 4);
  for (int c = 0; c < 3; ++c) {
    double sum = 0, sum2 = 0, level = 0;
    for (int y = 0; y < setup.height; ++y)
      for (int x = 0; x < setup.width; ++x) {
        const double d = double(reference.pixel(Film::kBeauty, x, y)[c]) -
                         double(power.pixel(Film::kBeauty, x, y)[c]);
        sum += d, sum2 += d * d, level += reference.pixel(Film::kBeauty, x, y)[c];
      }
    const double n = double(setup.width) * double(setup.height), mean = sum / n;
    const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    std::printf(" %s %+.6f (%.6f) %+.2f%%", names[c], mean, se, 100 * mean / (level / n));
  }
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"light_bvh_importance_bench: the light BVH's RMSE at equal time, cost per choice"};
  Setup setup;
  std::string size = "128x96";
  app.add_option("--size", size, "image size WxH");
  app.add_option("--ref-spp", setup.refSpp, "samples per pixel of the references");
  app.add_option("--ref-threads", setup.refThreads, "threads of the references");
  app.add_option("--spp", setup.spp, "spp of the measured render (1 thread)");
  app.add_option("--seeds", setup.seeds, "renders measured (seeds 1..N), their mean squared error")
      ->check(CLI::Range(1, 1000));
  app.add_option("--cache", setup.cacheDir, "folder that keeps the references between runs");
  app.add_option("--only", setup.only, "one scene: cornell, many, quads");
  bool noBias = false;
  app.add_flag("--no-bias-check", noBias, "skip the power-sampler render (unbiasedness)");
  CLI11_PARSE(app, argc, argv);
  setup.checkBias = !noBias;
  if (std::sscanf(size.c_str(), "%dx%d", &setup.width, &setup.height) != 2) return 2;
  measure("Cornell box (../shared/reference/cornell-box.gltf)", "cornell",
          loadGltf(std::string(TRAY_SOURCE_DIR) + "/../shared/reference/cornell-box.gltf"), setup);
  measure("many lights (tests/light_scenes.h manyLightsScene)", "many", test::manyLightsScene(),
          setup);
  measure("many quad lights (manyLightsScene(true))", "quads", test::manyLightsScene(true), setup);
  return 0;
}

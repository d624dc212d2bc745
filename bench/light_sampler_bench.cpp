// Light choice for next-event estimation: the power sampler (pbrt-v4's PowerLightSampler)
// against the light BVH (Conty Estevez & Kulla 2018; lights/bvh_light_sampler.h), measured in
// one run on three scenes: the shared Cornell box (one light), a sun beside a bright sky, and
// a ground under hundreds of small lamps (tests/light_scenes.h). For each: RMSE at equal spp
// against a converged BVH render, CPU time, and the time each needs to reach the error the
// power sampler has at the largest spp (RMSE^2 x time is constant for an unbiased estimator).
// Usage: light_sampler_bench [--size WxH] [--threads N] [--ref-spp N] [--spp N]
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "bench/image_error.h"
#include "bench/timed_render.h"
#include "gltf/gltf_loader.h"
#include "lights/bvh_light_sampler.h"
#include "lights/light_set.h"
#include "tests/light_scenes.h"

using namespace tray;

namespace {

struct Setup {
  int width = 96, height = 72, threads = 2, refSpp = 4096, spp = 64;
};

TimedFilm render(const Scene& scene, const Setup& setup, int spp, const char* chooser, int seed) {
  RenderSettings settings;
  settings.set("integrator", "path");
  settings.set("spp", spp);
  settings.set("seed", seed);
  settings.set("light-sampler", std::string(chooser));
  return timedRender(scene, setup.width, setup.height, settings, setup.threads);
}

void measure(const char* name, const Scene& scene, const Setup& setup) {
  std::printf("\n%s (%dx%d, reference %d spp bvh)\n", name, setup.width, setup.height,
              setup.refSpp);
  {
    const LightSet lights(scene, LightSamplerKind::kPower);
    std::vector<LightBounds> bounds;
    for (size_t i = 0; i < lights.size(); ++i) bounds.push_back(lights.light(i).bounds());
    const BvhLightSampler tree(bounds);
    std::printf("%zu lights; light BVH: %zu nodes, depth %d\n", lights.size(), tree.nodeCount(),
                tree.depth());
  }
  const Film reference = render(scene, setup, setup.refSpp, "bvh", 99).film;
  std::printf("| spp | power RMSE | power s | bvh RMSE | bvh s | RMSE ratio |\n");
  std::printf("|---|---|---|---|---|---|\n");
  double errors[2] = {0, 0}, seconds[2] = {0, 0};
  for (int spp = std::max(1, setup.spp / 16); spp <= setup.spp; spp *= 4) {
    const char* choosers[2] = {"power", "bvh"};
    for (int k = 0; k < 2; ++k) {
      const TimedFilm r = render(scene, setup, spp, choosers[k], 1);
      errors[k] = compareBeauty(r.film, reference).rmse;
      seconds[k] = r.seconds;
    }
    std::printf("| %d | %.5f | %.3f | %.5f | %.3f | %.2f |\n", spp, errors[0], seconds[0],
                errors[1], seconds[1], errors[0] / errors[1]);
  }
  // Time to the power sampler's error at the largest spp: the BVH's time scaled by
  // (its RMSE / that error)^2.
  const double bvhTime = seconds[1] * (errors[1] / errors[0]) * (errors[1] / errors[0]);
  std::printf(
      "time to RMSE %.5f: power %.3f s, bvh %.3f s: **%.2fx less time** with bvh; "
      "per sample bvh costs %.2fx power\n",
      errors[0], seconds[0], bvhTime, seconds[0] / bvhTime, seconds[1] / seconds[0]);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"light_sampler_bench: power vs light BVH at equal spp and equal error"};
  Setup setup;
  std::string size = "96x72";
  app.add_option("--size", size, "image size WxH");
  app.add_option("--threads", setup.threads, "render threads");
  app.add_option("--ref-spp", setup.refSpp, "samples per pixel of the references");
  app.add_option("--spp", setup.spp, "largest spp measured (also spp/4 and spp/16)");
  CLI11_PARSE(app, argc, argv);
  if (std::sscanf(size.c_str(), "%dx%d", &setup.width, &setup.height) != 2) return 2;
  measure("Cornell box (../shared/reference/cornell-box.gltf)",
          loadGltf(std::string(TRAY_SOURCE_DIR) + "/../shared/reference/cornell-box.gltf"), setup);
  measure("sun and sky (tests/light_scenes.h sunAndSkyScene)", test::sunAndSkyScene(), setup);
  measure("many lights (tests/light_scenes.h manyLightsScene)", test::manyLightsScene(), setup);
  return 0;
}

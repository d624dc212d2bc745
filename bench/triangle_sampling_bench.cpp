// Emissive triangles and rectangles (triangle pairs, lights/quad_lights.h) sampled by area, by
// solid angle and by pbrt-v4's choice between them (--triangle-sampling;
// lights/triangle_light_lanes.h, lights/rectangle_light_lanes.h), measured in one run on four
// scenes: the shared Cornell box against Mitsuba 3's reference (and its direct light alone), a
// large panel light against a wall and the many-lights ground with triangle lamps and with
// rectangle lamps (tests/light_scenes.h) against converged renders. For each mode: RMSE
// at equal spp (the whole image, and away from the light's own pixels, where the pixel
// filter's coverage noise dominates), Msamples per CPU-second, and RMSE at equal CPU time.
// Usage: triangle_sampling_bench [--threads N] [--ref-spp N] [--spp N] [--integrator path]
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "bench/image_error.h"
#include "bench/timed_render.h"
#include "gltf/gltf_loader.h"
#include "lights/light_set.h"
#include "tests/light_scenes.h"

using namespace tray;

namespace {

struct Setup {
  int threads = 1, refSpp = 2048, spp = 64, maxDepth = 8;
  std::string integrator = "path";
};

TimedFilm render(const Scene& scene, int w, int h, const Setup& setup, int spp, const char* mode,
                 int seed) {
  RenderSettings settings;
  settings.set("integrator", setup.integrator);
  settings.set("spp", spp);
  settings.set("seed", seed);
  settings.set("max-depth", setup.maxDepth);
  settings.set("triangle-sampling", std::string(mode));
  return timedRender(scene, w, h, settings, setup.threads);
}

/// RMSE over the pixels whose reference is at most 1 in every channel and that have no such
/// brighter pixel within 2 pixels (the light seen directly and its edges).
double offLightRmse(const Film& im, const Film& ref) {
  const int w = ref.width(), h = ref.height();
  const auto bright = [&](int x, int y) {
    const float* p = ref.pixel(Film::kBeauty, x, y);
    return std::max({p[0], p[1], p[2]}) > 1.0f;
  };
  double se = 0;
  long n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool near = false;
      for (int dy = -2; dy <= 2 && !near; ++dy)
        for (int dx = -2; dx <= 2 && !near; ++dx)
          near = x + dx >= 0 && x + dx < w && y + dy >= 0 && y + dy < h && bright(x + dx, y + dy);
      if (near) continue;
      const float *a = im.pixel(Film::kBeauty, x, y), *r = ref.pixel(Film::kBeauty, x, y);
      for (int c = 0; c < 3; ++c, ++n) se += double(a[c] - r[c]) * double(a[c] - r[c]);
    }
  return std::sqrt(se / double(n));
}

void measure(const char* name, const Scene& scene, int w, int h, const Film& reference,
             const Setup& setup) {
  std::printf("\n%s (%dx%d, %d thread(s), %s; %zu rectangle(s) found)\n", name, w, h, setup.threads,
              setup.integrator.c_str(),
              LightSet(scene, LightSamplerKind::kBvh, TriangleSampling::kAuto).rectangleCount());
  const char* modes[3] = {"area", "solid-angle", "auto"};
  std::printf("| spp | mode | RMSE | RMSE off the light | CPU s | Msamples/s |\n");
  std::printf("|---|---|---|---|---|---|\n");
  double error[3] = {0, 0, 0}, offLight[3] = {0, 0, 0}, seconds[3] = {0, 0, 0};
  for (int spp = std::max(1, setup.spp / 4); spp <= setup.spp; spp *= 4)
    for (int k = 0; k < 3; ++k) {
      const TimedFilm r = render(scene, w, h, setup, spp, modes[k], 1);
      error[k] = compareBeauty(r.film, reference).rmse;
      offLight[k] = offLightRmse(r.film, reference);
      seconds[k] = r.seconds;
      std::printf("| %d | %s | %.5f | %.5f | %.3f | %.3f |\n", spp, modes[k], error[k], offLight[k],
                  r.seconds, double(w) * h * spp / r.seconds * 1e-6);
    }
  // Equal time, as bench/light_sampler_bench.cpp: RMSE^2 x time is constant for an unbiased
  // estimator, so a mode's RMSE in area's time at the largest spp is its RMSE x
  // sqrt(its time / area's). (Rendering at a spp scaled by the speed instead would leave the
  // powers of two where Sobol' points are stratified.)
  std::printf("equal time (area's %.3f s at %d spp): RMSE", seconds[0], setup.spp);
  for (int k = 0; k < 3; ++k)
    std::printf("  %s %.5f (off the light %.5f)", modes[k],
                error[k] * std::sqrt(seconds[k] / seconds[0]),
                offLight[k] * std::sqrt(seconds[k] / seconds[0]));
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"triangle_sampling_bench: area vs solid-angle vs auto triangle sampling"};
  Setup setup;
  app.add_option("--threads", setup.threads, "render threads");
  app.add_option("--ref-spp", setup.refSpp, "spp of the converged references (built scenes)");
  app.add_option("--spp", setup.spp, "largest spp measured (also spp/4)");
  app.add_option("--integrator", setup.integrator, "path or path-scalar");
  CLI11_PARSE(app, argc, argv);
  const std::string shared = std::string(TRAY_SOURCE_DIR) + "/../shared/reference/";
  const Scene cornell = loadGltf(shared + "cornell-box.gltf");
  measure("Cornell box (../shared/reference/cornell-box.gltf, against Mitsuba 3)", cornell, 256,
          256, readReference(shared + "cornell-box.ref.exr"), setup);
  const Scene panel = test::panelByAWallScene(), many = test::manyLightsScene();
  Setup ref = setup, direct = setup;
  ref.threads = 2;
  direct.maxDepth = ref.maxDepth = 2;
  measure("Cornell box, direct light only (max depth 2, against a converged TRay render)", cornell,
          128, 128, render(cornell, 128, 128, ref, setup.refSpp, "auto", 99).film, direct);
  ref.maxDepth = 8;
  measure("panel by a wall (tests/light_scenes.h panelByAWallScene)", panel, 128, 96,
          render(panel, 128, 96, ref, setup.refSpp, "auto", 99).film, setup);
  measure("many lights (tests/light_scenes.h manyLightsScene)", many, 128, 96,
          render(many, 128, 96, ref, setup.refSpp, "auto", 99).film, setup);
  const Scene manyQuads = test::manyLightsScene(true);
  measure("many rectangle lights (manyLightsScene(true))", manyQuads, 128, 96,
          render(manyQuads, 128, 96, ref, setup.refSpp, "auto", 99).film, setup);
  return 0;
}

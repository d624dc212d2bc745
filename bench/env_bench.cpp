// Image-based lighting: time to a fixed error with the environment map importance-sampled
// (luminance x sin(theta), lights/image_environment_light.h) against uniform sphere sampling,
// both with MIS against BSDF sampling, measured in one run on a sun-in-sky scene (a diffuse
// floor, a diffuse sphere and a glossy sphere under bench/sky_maps.h's sky, whose 2-degree sun
// gives most of the light).
// Usage: env_bench [--size WxH] [--threads N] [--ref-spp N] [--write-maps DIR]
//   --write-maps writes sky.exr (the sun sky) and windows.exr into DIR, for tray-render --env.
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "bench/cpu_time.h"
#include "bench/image_error.h"
#include "bench/sky_maps.h"
#include "io/image_output.h"
#include "render/render_setup.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

using namespace tray;

namespace {

Scene sunScene(bool uniform) {
  Scene s;
  const int grey = test::addMaterial(s, test::diffuse(Color(0.6f)));
  Material glossy = test::diffuse(Color(0.8f, 0.5f, 0.3f));
  glossy.metallic = 1.0f, glossy.roughness = 0.3f;
  test::addShape(s, std::make_shared<Plane>(), Mat4::identity(), grey);
  test::addSphere(s, {-1.1f, 1, 0}, 1, grey);
  test::addSphere(s, {1.1f, 1, 0}, 1, test::addMaterial(s, glossy));
  s.environment.map = maps::sunSky(1024, 512);
  s.environment.uniformSampling = uniform;
  s.finalize();
  return s;
}

void writeMap(const EnvironmentMap& m, const std::string& path) {
  Film f(m.width, m.height);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      float* p = f.pixel(Film::kBeauty, x, y);
      const float* src = &m.rgb[(size_t(y) * size_t(m.width) + size_t(x)) * 3];
      p[0] = src[0], p[1] = src[1], p[2] = src[2], p[3] = 1;
    }
  ImageOutputOptions o;
  o.halfFloat = false;
  writeImage(f, path, o);
  std::printf("wrote %s (%dx%d)\n", path.c_str(), m.width, m.height);
}

struct Run {
  int spp;
  double seconds, rmse;
};

/// A path-traced film of `s` at `spp` and `seed` on Embree; `seconds` gets the CPU time.
Film renderPath(const Scene& s, const CameraDesc& cam, int w, int h, int spp, int seed,
                int threads, double& seconds) {
  RenderSettings st;
  st.set("integrator", "path");
  st.set("spp", spp);
  st.set("seed", seed);
  const double t0 = cpuSeconds();
  Film f = test::renderFilm(s, cam, w, h, st, nullptr, {}, "embree", threads);
  seconds = cpuSeconds() - t0;
  return f;
}

Run render(const Scene& s, const CameraDesc& cam, int w, int h, int spp, int threads,
           const Film& reference) {
  double seconds = 0;
  const Film f = renderPath(s, cam, w, h, spp, 7, threads, seconds);
  return {spp, seconds, compareBeauty(f, reference).rmse};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"env_bench: environment importance sampling vs uniform sphere sampling"};
  std::string size = "96x64", mapsDir;
  int threads = 2, refSpp = 4096;
  app.add_option("--size", size, "image size WxH")->capture_default_str();
  app.add_option("--threads", threads, "render threads")->capture_default_str();
  app.add_option("--ref-spp", refSpp, "samples per pixel of the reference")->capture_default_str();
  app.add_option("--write-maps", mapsDir, "write sky.exr and windows.exr into this folder");
  CLI11_PARSE(app, argc, argv);
  if (!mapsDir.empty()) {
    std::filesystem::create_directories(mapsDir);
    writeMap(*maps::sunSky(2048, 1024), mapsDir + "/sky.exr");
    writeMap(*maps::windows(1024, 512), mapsDir + "/windows.exr");
    return 0;
  }
  const ImageSize is = resolveImageSize(size, CameraDesc{});
  const int w = is.width, h = is.height;
  const Scene importance = sunScene(false), uniform = sunScene(true);
  const CameraDesc cam = test::lookAt({0, 2.5f, 6}, {0, 0.8f, 0}, 0.75f);

  double refSeconds = 0;
  const Film reference = renderPath(importance, cam, w, h, refSpp, 1, threads, refSeconds);
  std::printf("reference: %dx%d, %d spp, importance sampled: %.1f s CPU\n", w, h, refSpp,
              refSeconds);

  // The target: the error importance sampling reaches at 16 spp. Monte Carlo error falls as
  // 1 / sqrt(spp) and time grows as spp, so time to the target is t (rmse / target)^2, taken
  // from the largest run of each method (measured runs print beside it).
  std::printf("%-10s %6s %10s %10s\n", "sampling", "spp", "CPU s", "RMSE");
  Run last[2];
  double target = 0;
  for (int m = 0; m < 2; ++m) {
    const Scene& s = m == 0 ? importance : uniform;
    for (int spp : {4, 16, 64, 256}) {
      last[m] = render(s, cam, w, h, spp, threads, reference);
      if (m == 0 && spp == 16) target = last[m].rmse;
      std::printf("%-10s %6d %10.3f %10.5f\n", m == 0 ? "importance" : "uniform", spp,
                  last[m].seconds, last[m].rmse);
    }
  }
  double toTarget[2];
  for (int m = 0; m < 2; ++m)
    toTarget[m] = last[m].seconds * (last[m].rmse / target) * (last[m].rmse / target);
  std::printf("time to RMSE %.5f: importance %.3f s, uniform %.3f s: %.1fx less time with "
              "importance sampling\n",
              target, toTarget[0], toTarget[1], toTarget[1] / toTarget[0]);
  return 0;
}

// aa_bench: adaptive supersampling against the naive 4x4 grid at equal accuracy.
// Renders the scene's reference (32x32 grid, box filter), the 4x4 grid, and adaptive (inner
// whitted, depth 4) at falling thresholds; prints RMSE and camera rays of each, then the
// cheapest adaptive setting that reaches the grid's RMSE and its rays as a share of the grid's.
// Usage: aa_bench [scene.gltf] [WxH] [threads]   (default scenes/whitted.gltf at the CLI's
// default size, 640x480 for it; all cores)
#include <cstdio>
#include <string>

#include "accel/registry.h"
#include "bench/image_error.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"

using namespace tray;

namespace {

struct Run {
  Film film;
  RenderStats stats;
};

Run render(const Scene& scene, const CameraDesc& camera, ImageSize size, const RenderSettings& s,
           int threads) {
  RenderOptions opt;
  opt.threads = threads;
  RenderStats st;
  Film film = PreparedScene(scene, camera, size).render(s, opt, &st);
  return {std::move(film), st};
}

RenderSettings grid(int n) {
  RenderSettings s;
  s.set("integrator", "whitted");
  s.set("pixel-sampler", "grid");
  s.set("spp", n * n);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string path =
        argc > 1 ? argv[1] : std::string(TRAY_SOURCE_DIR) + "/scenes/whitted.gltf";
    Scene scene = loadGltf(path);
    scene.sourcePath = path;
    const CameraDesc cd = chooseCamera(scene, -1);
    const ImageSize size = resolveImageSize(argc > 2 ? argv[2] : "", cd);
    const int threads = argc > 3 ? std::stoi(argv[3]) : 0;
    const double pixels = double(size.width) * size.height;

    std::printf("%s %dx%d: reference = 32x32 grid, whitted, box filter\n", path.c_str(), size.width,
                size.height);
    const Run reference = render(scene, cd, size, grid(32), threads);
    const Run grid4 = render(scene, cd, size, grid(4), threads);
    const double gridRmse = compareBeauty(grid4.film, reference.film).rmse;
    const double gridRays = double(grid4.stats.rays.cameraRays);
    std::printf("%-28s %12s %10s %10s %9s\n", "method", "camera rays", "rays/px", "RMSE",
                "seconds");
    std::printf("%-28s %12.0f %10.2f %10.3e %9.3f\n", "grid 4x4", gridRays, gridRays / pixels,
                gridRmse, grid4.stats.seconds);

    double bestShare = -1, bestRmse = 0, bestThreshold = 0;
    for (float t : {0.2f, 0.1f, 0.05f, 0.03f, 0.02f, 0.01f, 0.005f}) {
      RenderSettings s;
      s.set("integrator", "adaptive");
      s.set("inner", "whitted");
      s.set("aa-depth", 4);
      s.set("aa-threshold", t);
      const Run a = render(scene, cd, size, s, threads);
      const double rays = double(a.stats.rays.cameraRays);
      const double e = compareBeauty(a.film, reference.film).rmse;
      char name[64];
      std::snprintf(name, sizeof name, "adaptive threshold=%.3f", t);
      std::printf("%-28s %12.0f %10.2f %10.3e %9.3f\n", name, rays, rays / pixels, e,
                  a.stats.seconds);
      if (e <= gridRmse && (bestShare < 0 || rays / gridRays < bestShare))
        bestShare = rays / gridRays, bestRmse = e, bestThreshold = t;
    }
    if (bestShare < 0) {
      std::printf("no adaptive setting reached the 4x4 grid's RMSE %.3e\n", gridRmse);
      return 1;
    }
    std::printf(
        "adaptive (threshold %.3f) reaches RMSE %.3e <= grid 4x4 RMSE %.3e with %.1f%% of "
        "its camera rays (target: at most 35%%)\n",
        bestThreshold, bestRmse, gridRmse, 100 * bestShare);
    return bestShare <= 0.35 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "aa_bench: %s\n", e.what());
    return 2;
  }
}

// surface_bench: the wavefront's surface stage (integrators/surface_batch.h, SIMD over a queue of
// hits) against Scene::surface called hit by hit, on one thread, in Mhits per CPU-second, on
// the hits of camera rays (coherent: few primitives per wave) and of bounce rays (incoherent)
// from bench/bench_rays.h, in waves of the wavefront's size. The SIMD stage runs with the
// CPU's best target and with each narrower one (forced). Modes take turns over the rounds and
// each keeps its best, so other processes' load slows all alike. Figures only, not a test.
//
//   surface_bench [SCENE.gltf ...] [--size W H] [--rounds N]
// (default: the shared Cornell box and MetalRoughSpheresNoTextures, 320 x 240, 5 rounds)
#include <hwy/targets.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "accel/registry.h"
#include "bench/bench_rays.h"
#include "bench/cpu_time.h"
#include "core/error.h"
#include "integrators/surface_batch.h"
#include "integrators/path_wavefront.h"
#include "gltf/gltf_loader.h"

using namespace tray;

namespace {

/// The wavefront integrator's queue size.
constexpr size_t kWave = kPathWaveSize;

/// A ray set's hits, wave by wave, as the wavefront's bounce() sees them.
struct Waves {
  std::vector<Ray> rays;
  std::vector<Hit> hits;
  std::vector<uint8_t> found;
  size_t hitCount = 0;
};

Waves trace(const Accelerator& accel, const std::vector<Ray>& rays) {
  Waves w;
  w.rays = rays;
  w.hits.resize(rays.size());
  w.found.resize(rays.size());
  for (size_t b = 0; b < rays.size(); b += kWave) {
    const size_t n = std::min(kWave, rays.size() - b);
    accel.intersectBatch(std::span(w.rays.data() + b, n), std::span(w.hits.data() + b, n),
                         std::span(w.found.data() + b, n));
  }
  for (uint8_t f : w.found) w.hitCount += f;
  return w;
}

/// Mhits per CPU-second of one way over all waves, repeated for at least 0.2 CPU-seconds;
/// `simd`: SurfaceBatch::compute, else Scene::surface per found hit.
double measure(const Scene& scene, const SurfaceBatch& batch, const Waves& w, bool simd) {
  std::vector<SurfacePoint> out(kWave);
  SurfaceBatch::Scratch scratch;
  size_t done = 0;
  float checksum = 0;
  const double start = cpuSeconds();
  do {
    for (size_t b = 0; b < w.rays.size(); b += kWave) {
      const size_t n = std::min(kWave, w.rays.size() - b);
      const std::span rays(w.rays.data() + b, n);
      const std::span hits(w.hits.data() + b, n);
      const std::span found(w.found.data() + b, n);
      if (simd) {
        batch.compute(rays, hits, found, std::span(out.data(), n), scratch);
      } else {
        for (size_t j = 0; j < n; ++j)
          if (found[j]) out[j] = scene.surface(rays[j], hits[j]);
      }
      checksum += out[n / 2].p.x;
    }
    done += w.hitCount;
  } while (cpuSeconds() - start < 0.2);
  if (checksum == 12345.0f) std::printf("(checksum)\n");  // keeps the work from being elided
  return double(done) / (cpuSeconds() - start) * 1e-6;
}

void benchScene(const std::string& path, int width, int height, int rounds) {
  const Scene scene = loadGltf(path);
  const bench::RaySet rays = bench::makeRays(scene, width, height, true);
  const auto accel = makeAccelerator("embree", scene);
  const Waves sets[2] = {trace(*accel, rays.camera), trace(*accel, rays.bounce)};
  const SurfaceBatch batch(scene);
  if (!batch.useful()) {
    std::printf("%s: no static triangle mesh, or no SIMD target\n", path.c_str());
    return;
  }
  // The scalar loop, then the SIMD stage on each target this CPU has (best first).
  std::vector<int64_t> targets;
  for (int64_t t : hwy::SupportedAndGeneratedTargets())
    if (t != HWY_SCALAR && t != HWY_EMU128) targets.push_back(t);
  std::vector<double> best(2 * (1 + targets.size()), 0.0);
  for (int r = 0; r < rounds; ++r)
    for (int s = 0; s < 2; ++s) {
      best[2 * 0 + s] = std::max(best[2 * 0 + s], measure(scene, batch, sets[s], false));
      for (size_t t = 0; t < targets.size(); ++t) {
        hwy::SetSupportedTargetsForTest(targets[t]);
        best[2 * (1 + t) + s] =
            std::max(best[2 * (1 + t) + s], measure(scene, batch, sets[s], true));
      }
      hwy::SetSupportedTargetsForTest(0);
    }
  std::printf("%s: %zu camera-ray hits, %zu bounce-ray hits; 1 thread, waves of %zu\n",
              std::filesystem::path(path).filename().c_str(), sets[0].hitCount, sets[1].hitCount,
              kWave);
  std::printf("  %-28s %18s %18s\n", "Mhits per CPU-second", "camera", "bounce");
  std::printf("  %-28s %8.2f %9s %8.2f\n", "Scene::surface, hit by hit", best[0], "", best[1]);
  for (size_t t = 0; t < targets.size(); ++t)
    std::printf("  %-28s %8.2f (%5.2fx) %8.2f (%5.2fx)\n",
                ("SurfaceBatch, " + std::string(hwy::TargetName(targets[t]))).c_str(),
                best[2 * (1 + t)], best[2 * (1 + t)] / best[0], best[2 * (1 + t) + 1],
                best[2 * (1 + t) + 1] / best[1]);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes;
  int width = 320, height = 240, rounds = 5;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--size") && i + 2 < argc) {
      width = std::atoi(argv[++i]), height = std::atoi(argv[++i]);
      continue;
    }
    if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc) {
      rounds = std::atoi(argv[++i]);
      continue;
    }
    scenes.push_back(argv[i]);
  }
  if (scenes.empty())
    scenes = {TRAY_SOURCE_DIR "/../shared/reference/cornell-box.gltf",
              TRAY_SOURCE_DIR "/../shared/gltf-samples/MetalRoughSpheresNoTextures.glb"};
  try {
    for (const std::string& s : scenes) benchScene(s, width, height, rounds);
  } catch (const Error& e) {
    std::fprintf(stderr, "surface_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}

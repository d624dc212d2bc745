// batch_bench: batched queries (Accelerator::intersectBatch / occludedBatch, what the wavefront
// integrator calls) against single-ray queries, on one thread, in Mrays per CPU-second: every
// batched way of each accelerator, Embree's (rtcIntersect1 loop, rtcIntersect1M stream,
// rtcIntersect8 packets) and the in-house BVH's (single-ray loop, 8-ray packets, 64-ray
// streams, accel/bvh_batch.cpp), on coherent camera rays, shadow rays towards a point light and
// incoherent diffuse bounce rays (bench/bench_rays.h). The modes take turns over the rounds and
// each keeps its best, so load from other processes slows all alike. Figures only, not a test.
//
//   batch_bench [SCENE.gltf ...] [--size W H] [--rounds N] [--camera] [--save-rays DIR]
// (default: the shared Cornell box and MetalRoughSpheresNoTextures, 320 x 240, 5 rounds)
// --camera: camera rays from the scene's own camera (as the renderer's), not a framing of its
// bounds. --save-rays: each ray set as DIR/SCENE-{camera,shadow,bounce}.f32, eight float32 per
// ray (origin, direction, tmin, tmax), so that another renderer traces the very same rays
// (bench/mitsuba_traversal.py).
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "accel/bvh_accelerator.h"
#include "accel/embree_accelerator.h"
#include "bench/bench_rays.h"
#include "bench/cpu_time.h"
#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "integrators/path_wavefront.h"

using namespace tray;

namespace {

/// The wavefront integrator's queue size.
constexpr size_t kBatch = kPathWaveSize;

struct Mode {
  std::string name;
  std::unique_ptr<Accelerator> accel;
  bool coherent = false;  ///< camera rays through intersectCoherentBatch (the wavefront's)
  double camera = 0, shadow = 0, bounce = 0;  ///< best Mrays per CPU-second
};

/// Mrays per CPU-second of one query over a ray set in batches of kBatch, repeated for at least
/// `minSeconds` of CPU time.
double batchedMrays(const Accelerator& accel, const std::vector<Ray>& rays, bool shadow,
                    double minSeconds, bool coherent = false) {
  if (rays.empty()) return 0;
  std::vector<Hit> hits(kBatch);
  std::vector<uint8_t> flags(kBatch);
  size_t traced = 0, found = 0;
  const double start = cpuSeconds();
  do {
    for (size_t b = 0; b < rays.size(); b += kBatch) {
      const size_t n = std::min(kBatch, rays.size() - b);
      const std::span<const Ray> batch(rays.data() + b, n);
      if (shadow)
        accel.occludedBatch(batch, std::span(flags.data(), n));
      else if (coherent)
        accel.intersectCoherentBatch(batch, std::span(hits.data(), n), std::span(flags.data(), n));
      else
        accel.intersectBatch(batch, std::span(hits.data(), n), std::span(flags.data(), n));
      for (size_t i = 0; i < n; ++i) found += flags[i];
    }
    traced += rays.size();
  } while (cpuSeconds() - start < minSeconds);
  if (found == 0) std::printf("(no hits)\n");  // keeps the queries from being optimised out
  return double(traced) / (cpuSeconds() - start) * 1e-6;
}

std::vector<Mode> modes(const Scene& scene) {
  std::vector<Mode> m;
  m.push_back({"embree rtcIntersect1 loop", makeEmbreeAccelerator(scene, EmbreeBatch::kLoop)});
  m.push_back({"embree rtcIntersect1M", makeEmbreeAccelerator(scene, EmbreeBatch::kStream)});
  m.push_back({"embree rtcIntersect8", makeEmbreeAccelerator(scene, EmbreeBatch::kPacket8)});
  m.push_back(
      {"embree rtcIntersect8 coherent", makeEmbreeAccelerator(scene, EmbreeBatch::kPacket8), true});
  for (BvhBatch batch : {BvhBatch::kLoop, BvhBatch::kPacket8, BvhBatch::kStream64}) {
    TwoLevelOptions options;
    options.batch = batch;
    const int rays = bvhBatchRays(batch);
    m.push_back({rays == 1 ? "bvh single-ray loop" : "bvh " + std::to_string(rays) + "-ray groups",
                 makeTwoLevelAccelerator(scene, options)});
  }
  return m;
}

/// A ray set as float32 (o, d, tmin, tmax) per ray, for bench/mitsuba_traversal.py.
void saveRays(const std::vector<Ray>& rays, const std::filesystem::path& file) {
  std::ofstream out(file, std::ios::binary);
  for (const Ray& r : rays) {
    const float v[8] = {r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z, r.tmin, r.tmax};
    out.write(reinterpret_cast<const char*>(v), sizeof v);
  }
  if (!out) throw Error("cannot write " + file.string());
}

void benchScene(const std::string& path, int width, int height, int rounds, bool sceneCamera,
                const std::string& saveDir) {
  const Scene scene = loadGltf(path);
  const bench::RaySet rays = bench::makeRays(scene, width, height, sceneCamera);
  if (!saveDir.empty()) {
    const std::string stem = std::filesystem::path(path).stem().string();
    saveRays(rays.camera, std::filesystem::path(saveDir) / (stem + "-camera.f32"));
    saveRays(rays.shadow, std::filesystem::path(saveDir) / (stem + "-shadow.f32"));
    saveRays(rays.bounce, std::filesystem::path(saveDir) / (stem + "-bounce.f32"));
  }
  std::vector<Mode> all = modes(scene);
  for (int r = 0; r < rounds; ++r)
    for (Mode& m : all) {
      m.camera = std::max(m.camera, batchedMrays(*m.accel, rays.camera, false, 0.2, m.coherent));
      m.shadow = std::max(m.shadow, batchedMrays(*m.accel, rays.shadow, true, 0.2));
      m.bounce = std::max(m.bounce, batchedMrays(*m.accel, rays.bounce, false, 0.2));
    }
  std::printf("%s: %dx%d camera rays, %zu shadow and bounce rays; 1 thread, batches of %zu\n",
              std::filesystem::path(path).filename().c_str(), width, height, rays.shadow.size(),
              kBatch);
  std::printf("  %-26s %18s %18s %18s\n", "Mrays per CPU-second", "camera", "shadow", "bounce");
  const Mode* loop = nullptr;
  for (const Mode& m : all) {
    if (m.name.find("loop") != std::string::npos) loop = &m;  // each accelerator's loop first
    std::printf("  %-26s %8.2f (%5.2fx) %8.2f (%5.2fx) %8.2f (%5.2fx)\n", m.name.c_str(), m.camera,
                m.camera / loop->camera, m.shadow, m.shadow / loop->shadow, m.bounce,
                m.bounce / loop->bounce);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> scenes;
  int width = 320, height = 240, rounds = 5;
  bool sceneCamera = false;
  std::string saveDir;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--camera")) {
      sceneCamera = true;
      continue;
    }
    if (!std::strcmp(argv[i], "--save-rays") && i + 1 < argc) {
      saveDir = argv[++i];
      continue;
    }
    if (!std::strcmp(argv[i], "--size") && i + 2 < argc) {
      width = std::atoi(argv[++i]);
      height = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc) {
      rounds = std::max(1, std::atoi(argv[++i]));
    } else {
      scenes.push_back(argv[i]);
    }
  }
  const std::string shared = TRAY_SOURCE_DIR "/../shared";
  if (scenes.empty())
    scenes = {shared + "/reference/cornell-box.gltf",
              shared + "/gltf-samples/MetalRoughSpheresNoTextures.glb"};
  std::printf("(ratios: each accelerator's batched ways over its own single-ray loop)\n");
  try {
    for (const std::string& s : scenes) benchScene(s, width, height, rounds, sceneCamera, saveDir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "batch_bench: %s\n", e.what());
    return 2;
  }
  return 0;
}

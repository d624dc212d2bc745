// accel_bench: build time, memory and ray throughput of every accelerator (embree, bvh (binned
// SAH), bvh-gs (Goldsmith–Salmon), naive where it finishes) on the same scenes and the same rays:
// camera rays, shadow rays towards a light, and diffuse-bounce rays from the camera hits.
// Prints a table, writes CSV for tools/plot_accel.py, and the teapot speed-up table
// (naive -> bvh -> embree) measured in this one run. Not a test: figures only. bvh-nocache is
// bvh without the last-occluder cache (its shadow rays only). Throughput is per CPU second
// times the cores (see throughput()), so a busy shared machine does not distort the ratios.
//
//   accel_bench [--csv FILE] [--max-triangles N] [--shared DIR] [--scene NAME] [--accel NAME]
// (--scene and --accel keep only the scene / the accelerators so named, e.g. --accel embree,bvh).
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "accel/bvh_accelerator.h"
#include "accel/registry.h"
#include "bench/bench_meshes.h"
#include "bench/bench_rays.h"
#include "bench/cpu_time.h"
#include "core/accelerator.h"
#include "core/camera.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "gltf/gltf_loader.h"

using namespace tray;
using Clock = std::chrono::steady_clock;

namespace {

/// The 1, 5 and 15 minute load averages (Linux), to show how busy a shared machine was.
std::string loadAverage() {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  f >> a >> b >> c;
  return f ? a + " " + b + " " + c : "unknown";
}

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct BenchScene {
  std::string name;
  Scene scene;
  size_t triangles = 0;
};

size_t countTriangles(const Scene& s) {
  size_t n = 0;
  for (const Primitive& p : s.primitives)
    if (p.kind == Primitive::Kind::kMesh) n += s.meshes[p.mesh].triangleCount();
  return n;
}

BenchScene meshScene(const std::string& name, TriangleMesh mesh) {
  BenchScene b{name, {}, 0};
  Material diffuse;
  b.scene.materials.push_back(diffuse);
  b.scene.meshes.push_back(std::move(mesh));
  Primitive p;
  p.mesh = 0;
  b.scene.primitives.push_back(p);
  b.scene.finalize();
  b.triangles = countTriangles(b.scene);
  return b;
}

enum class Query { kClosest, kOccluded };

/// Mrays/s of one query over a ray set, all cores, repeated for at least `minSeconds`. On a
/// shared machine the wall clock also counts the time other processes held the cores, so the
/// rate is rays per CPU second of this process times the cores it runs on: what a dedicated
/// machine with those cores traces (the same as the wall-clock rate on an idle machine).
double throughput(const Accelerator& accel, const std::vector<Ray>& rays, Query q,
                  double minSeconds) {
  if (rays.empty()) return 0;
  size_t traced = 0;
  auto t0 = Clock::now();
  const double cpu0 = cpuSeconds();
  do {
    size_t found = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, rays.size(), 256), size_t(0),
        [&](const tbb::blocked_range<size_t>& r, size_t acc) {
          Hit h;
          for (size_t i = r.begin(); i < r.end(); ++i)
            acc += q == Query::kClosest ? accel.intersect(rays[i], h) : accel.occluded(rays[i]);
          return acc;
        },
        std::plus<size_t>());
    (void)found;
    traced += rays.size();
  } while (secondsSince(t0) < minSeconds);
  const double cores = tbb::this_task_arena::max_concurrency();
  return double(traced) / (cpuSeconds() - cpu0) * cores * 1e-6;
}

struct Row {
  std::string scene, accel;
  size_t triangles = 0;
  double buildMs = 0, buildCpuMs = 0, bytesPerTriangle = 0, sah = 0, camera = 0, shadow = 0,
         bounce = 0;
};

/// One accelerator of one scene: built (best of several builds), then traced.
struct Candidate {
  Row row;
  std::unique_ptr<Accelerator> accel;
  bench::RaySet rays;  ///< naive traces a slice of the rays, or it would take minutes
};

Candidate build(const BenchScene& bs, const std::string& accelName,
                const bench::RaySet& rays) {
  Candidate c{{bs.name, accelName, bs.triangles}, nullptr, rays};
  // Best of three builds (first-touch and thread start-up dominate small scenes; other
  // processes on a shared machine add noise to large ones). One for the slow incremental build.
  int builds = bs.triangles < 200000 || accelName != "bvh-gs" ? 3 : 1;
  c.row.buildMs = 1e30;
  for (int i = 0; i < builds; ++i) {
    c.accel.reset();
    auto t0 = Clock::now();
    const double cpu0 = cpuSeconds();
    if (accelName == "bvh-nocache") {
      TwoLevelOptions o;
      o.occluderCache = false;
      c.accel = makeTwoLevelAccelerator(bs.scene, o);
    } else {
      c.accel = makeAccelerator(accelName, bs.scene);
    }
    const double ms = secondsSince(t0) * 1e3;
    if (ms < c.row.buildMs) c.row.buildMs = ms, c.row.buildCpuMs = (cpuSeconds() - cpu0) * 1e3;
  }
  c.row.bytesPerTriangle =
      double(c.accel->memoryBytes()) / double(std::max<size_t>(bs.triangles, 1));
  c.row.sah = bvhQuality(*c.accel).meshSahCost;
  if (accelName == "naive") {
    auto slice = [&](std::vector<Ray>& v) {
      size_t keep =
          std::min(v.size(), std::max<size_t>(256, 4000000 / std::max<size_t>(bs.triangles, 1)));
      std::vector<Ray> out;
      for (size_t i = 0; i < keep; ++i) out.push_back(v[i * v.size() / keep]);
      v = std::move(out);
    };
    slice(c.rays.camera), slice(c.rays.shadow), slice(c.rays.bounce);
  }
  return c;
}

/// Traces every candidate's rays in rounds, the accelerators taking turns, and keeps each one's
/// best round: load from other processes then slows all of them alike and the ratios hold.
void trace(std::vector<Candidate>& cands, int rounds) {
  for (int r = 0; r < rounds; ++r)
    for (Candidate& c : cands) {
      if (c.row.accel == "bvh-nocache") {  // differs from bvh in shadow rays only
        c.row.shadow =
            std::max(c.row.shadow, throughput(*c.accel, c.rays.shadow, Query::kOccluded, 0.2));
        continue;
      }
      c.row.camera =
          std::max(c.row.camera, throughput(*c.accel, c.rays.camera, Query::kClosest, 0.2));
      c.row.shadow =
          std::max(c.row.shadow, throughput(*c.accel, c.rays.shadow, Query::kOccluded, 0.2));
      c.row.bounce =
          std::max(c.row.bounce, throughput(*c.accel, c.rays.bounce, Query::kClosest, 0.2));
    }
}

void printRow(const Row& r) {
  std::printf("%-14s %9zu  %-11s %8.1f %8.1f %9.1f %8.1f %9.3g %9.3g %9.3g\n", r.scene.c_str(),
              r.triangles, r.accel.c_str(), r.buildMs, r.buildCpuMs, r.bytesPerTriangle, r.sah,
              r.camera, r.shadow, r.bounce);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  std::string csvPath = "accel_bench.csv";
  std::string shared = TRAY_SOURCE_DIR "/../shared";
  size_t maxTriangles = 2100000;
  std::string onlyScene, onlyAccel;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--csv")) csvPath = argv[i + 1];
    if (!std::strcmp(argv[i], "--max-triangles")) maxTriangles = std::stoul(argv[i + 1]);
    if (!std::strcmp(argv[i], "--shared")) shared = argv[i + 1];
    if (!std::strcmp(argv[i], "--scene")) onlyScene = argv[i + 1];
    if (!std::strcmp(argv[i], "--accel")) onlyAccel = argv[i + 1];
  }
  const size_t kNaiveLimit = 60000;  // naive beyond this would take hours

  std::vector<BenchScene> scenes;
  scenes.push_back(meshScene("teapot", bench::teapot(32)));
  for (const char* sample : {"Duck.glb", "DamagedHelmet.glb", "MetalRoughSpheresNoTextures.glb"}) {
    std::string path = shared + "/gltf-samples/" + sample;
    if (!std::filesystem::exists(path)) continue;
    Scene s = loadGltf(path);
    size_t n = countTriangles(s);
    scenes.push_back({std::filesystem::path(sample).stem().string(), std::move(s), n});
  }
  for (size_t n : {1000, 10000, 100000, 1000000, 2000000})
    if (n <= maxTriangles)
      scenes.push_back(
          meshScene("sphere-" + std::to_string(n / 1000) + "k", bench::bumpySphere(n)));

  std::printf("%-14s %9s  %-11s %8s %8s %9s %8s %9s %9s %9s\n", "scene", "triangles", "accel",
              "build ms", "cpu ms", "bytes/tri", "SAH", "camera", "shadow", "bounce");
  std::printf("%-14s %9s  %-11s %8s %8s %9s %8s %9s %9s %9s\n", "", "", "", "", "", "", "",
              "Mrays/s", "Mrays/s", "Mrays/s");
  std::printf("(%d threads; load average %s)\n", tbb::this_task_arena::max_concurrency(),
              loadAverage().c_str());
  std::vector<Row> rows;
  for (const BenchScene& bs : scenes) {
    if (!onlyScene.empty() && bs.name != onlyScene) continue;
    bench::RaySet rays = bench::makeRays(bs.scene, 320, 240);
    std::vector<Candidate> cands;
    // bvh-nocache: bvh without the last-occluder cache, to measure what the cache buys.
    for (const char* accel : {"embree", "bvh", "bvh-nocache", "bvh-gs", "naive"}) {
      if (std::string(accel) == "naive" && bs.triangles > kNaiveLimit) continue;
      if (!onlyAccel.empty() &&
          ("," + onlyAccel + ",").find("," + std::string(accel) + ",") == std::string::npos)
        continue;
      cands.push_back(build(bs, accel, rays));
    }
    trace(cands, 3);
    for (Candidate& c : cands) {
      rows.push_back(c.row);
      printRow(rows.back());
    }
  }

  std::ofstream csv(csvPath);
  csv << "scene,triangles,accel,build_ms,build_cpu_ms,bytes_per_triangle,sah_cost,camera_mrays,"
         "shadow_mrays,"
         "bounce_mrays\n";
  for (const Row& r : rows)
    csv << r.scene << ',' << r.triangles << ',' << r.accel << ',' << r.buildMs << ','
        << r.buildCpuMs << ',' << r.bytesPerTriangle << ',' << r.sah << ',' << r.camera << ','
        << r.shadow << ',' << r.bounce << '\n';
  std::printf("\nwrote %s (load average at the end: %s)\n", csvPath.c_str(), loadAverage().c_str());

  // The seed's progression on its teapot: each step's speed-up, from the rows above.
  auto find = [&](const std::string& scene, const std::string& accel) -> const Row* {
    for (const Row& r : rows)
      if (r.scene == scene && r.accel == accel) return &r;
    return nullptr;
  };
  const Row *naive = find("teapot", "naive"), *bvh = find("teapot", "bvh"),
            *embree = find("teapot", "embree");
  if (naive && bvh && embree) {
    std::printf("\nteapot (%zu triangles), speed-up of each step (same rays, this run):\n",
                bvh->triangles);
    std::printf("%-8s %12s %12s %12s\n", "rays", "naive->bvh", "bvh->embree", "naive->embree");
    auto line = [](const char* what, double n, double b, double e) {
      std::printf("%-8s %11.1fx %11.2fx %11.1fx\n", what, b / n, e / b, e / n);
    };
    line("camera", naive->camera, bvh->camera, embree->camera);
    line("shadow", naive->shadow, bvh->shadow, embree->shadow);
    line("bounce", naive->bounce, bvh->bounce, embree->bounce);
  }
  return 0;
}

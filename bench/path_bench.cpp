// Path tracing throughput on the Cornell box (512x512, 64 spp, max depth 8), against raw
// Embree traversal of incoherent rays measured in the same run on the same threads.
// Usage: path_bench [scene.gltf] [threads] [size] [spp]
//   (default: the shared Cornell box, 2 threads, 512, 64; smaller runs serve for profiling)
#include <sys/resource.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cstdio>

#include "core/renderer.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "integrators/path.h"
#include "io/gltf_loader.h"

using namespace tray;

/// CPU seconds used by this process so far, all threads: on a machine shared with other work
/// the wall-clock time depends on the load, the CPU time much less.
double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// Closest-hit queries per second for rays with random origins inside the scene bounds and
/// uniformly random directions: the incoherent workload a path tracer's bounces produce.
double rawTraversalMrays(const Accelerator& accel, const Bounds3& b, int threads) {
  const int kRays = 4'000'000, kChunk = 4096;
  std::atomic<int> hits{0};
  auto start = std::chrono::steady_clock::now();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(0, kRays / kChunk, [&](int chunk) {
      int local = 0;
      for (int i = 0; i < kChunk; ++i) {
        Sampler s(uint32_t(chunk), uint32_t(i), 42);
        Vec3 o = b.lo + Vec3(s.next1D(), s.next1D(), s.next1D()) * b.diagonal();
        Hit hit;
        local += accel.intersect(Ray{o, sampleUniformSphere(s.next2D())}, hit);
      }
      hits += local;
    });
  });
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return kRays / seconds * 1e-6;
}

int main(int argc, char** argv) {
  std::string path =
      argc > 1 ? argv[1] : std::string(TRAY_SOURCE_DIR) + "/../shared/reference/cornell-box.gltf";
  int threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int size = argc > 3 ? std::atoi(argv[3]) : 512, spp = argc > 4 ? std::atoi(argv[4]) : 64;
  Scene scene = loadGltf(path);
  auto camera = Camera::create(scene.cameras.at(0), size, size);
  auto accel = makeAccelerator("embree", scene);
  RenderSettings settings;
  settings.integrator = "path";
  settings.spp = spp;
  settings.maxDepth = 8;
  RenderContext ctx{scene, *accel, *camera, settings, size, size};
  auto integrator = makeIntegrator(ctx);
  Film film(size, size);
  RenderOptions options;
  options.threads = threads;
  const double cpuStart = cpuSeconds();
  RenderStats stats = renderImage(*integrator, film, options);
  const double cpu = cpuSeconds() - cpuStart;
  double samples = double(size) * size * spp;
  double raw = rawTraversalMrays(*accel, scene.bounds(), threads);
  std::printf("path tracing %s: %dx%d, %d spp, max depth 8, %d threads\n", path.c_str(), size, size,
              spp, threads);
  std::printf("  time            %.2f s\n", stats.seconds);
  std::printf("  Msamples/s      %.3f\n", samples / stats.seconds * 1e-6);
  std::printf(
      "  CPU time        %.2f s: %.3f Msamples per CPU-second (x %d threads = %.3f "
      "Msamples/s on idle cores)\n",
      cpu, samples / cpu * 1e-6, threads, samples / cpu * 1e-6 * threads);
  std::printf("  Mrays/s         %.2f (camera %.1fM, bounce %.1fM, shadow %.1fM)\n",
              stats.mraysPerSecond(), stats.rays.cameraRays * 1e-6, stats.rays.secondaryRays * 1e-6,
              stats.rays.shadowRays * 1e-6);
  std::printf("  raw Embree      %.2f Mrays/s (incoherent closest hits)\n", raw);
  std::printf("  path / raw      %.2f\n", stats.mraysPerSecond() / raw);
  std::printf("  NaN samples     %llu\n", (unsigned long long)stats.rays.nanSamples);
  return 0;
}

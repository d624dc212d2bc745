// Path tracing throughput on the Cornell box (512x512, 64 spp, max depth 8): the scalar
// `path` and `path-wavefront` side by side, against raw Embree traversal of incoherent rays,
// measured in the same run on the same threads.
// Usage: path_bench [scene.gltf] [threads] [size] [spp] [--accel NAME] [--no-replay]
//   [--batch-modes]
//   (default: the shared Cornell box, 2 threads, 512, 64; smaller runs serve for profiling)
#include <sys/resource.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <mutex>

#include "accel/bvh_accelerator.h"
#include "accel/embree_accelerator.h"
#include "accel/registry.h"
#include "bench/cpu_time.h"
#include "bench/image_error.h"
#include "core/error.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "gltf/gltf_loader.h"
#include "integrators/path.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"

using namespace tray;

/// CPU seconds used by this process so far, all threads: on a machine shared with other work
/// the wall-clock time depends on the load, the CPU time much less.
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

/// Forwards to an accelerator and keeps a copy of every query, so that the path tracer's own
/// rays can be replayed through bare traversal afterwards.
class RecordingAccelerator final : public Accelerator {
 public:
  explicit RecordingAccelerator(const Accelerator& inner) : inner_(inner) {}
  bool intersect(const Ray& ray, Hit& hit) const override {
    std::lock_guard<std::mutex> lock(mutex_);
    closest.push_back(ray);
    return inner_.intersect(ray, hit);
  }
  bool occluded(const Ray& ray) const override {
    std::lock_guard<std::mutex> lock(mutex_);
    shadow.push_back(ray);
    return inner_.occluded(ray);
  }
  void allHits(const Ray& ray, std::vector<Hit>& hits) const override { inner_.allHits(ray, hits); }
  mutable std::vector<Ray> closest, shadow;

 private:
  const Accelerator& inner_;
  mutable std::mutex mutex_;
};

/// Seconds to trace the rays (closest hits or occlusion) on `threads` threads.
double replaySeconds(const Accelerator& accel, const std::vector<Ray>& rays, bool shadow,
                     int threads) {
  std::atomic<int> hits{0};
  auto start = std::chrono::steady_clock::now();
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(size_t(0), (rays.size() + 4095) / 4096, [&](size_t chunk) {
      int local = 0;
      for (size_t i = chunk * 4096; i < std::min(rays.size(), chunk * 4096 + 4096); ++i) {
        Hit hit;
        local += shadow ? accel.occluded(rays[i]) : accel.intersect(rays[i], hit);
      }
      hits += local;
    });
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Error at equal samples, and so equal-error speed: both random sequences render the scene at
/// the reference's size with `base`'s settings; the RMSE of each against the reference gives
/// how many independent samples a Sobol' sample is worth (the MSE ratio).
void equalError(const Scene& scene, const Accelerator& accel, const std::string& refPath,
                RenderSettings base, int threads) {
  if (!std::filesystem::exists(refPath)) return;
  const Film ref = readReference(refPath);
  const int w = ref.width(), h = ref.height();
  const PreparedScene prepared(scene, scene.cameras.at(0), {w, h}, accel);
  std::printf("equal error: %dx%d, %d spp, against %s\n", w, h, base.getInt("spp"),
              refPath.c_str());
  double mse[2], rate[2];
  const char* names[2] = {"independent", "sobol"};
  for (int k = 0; k < 2; ++k) {
    base.set("sampler", names[k]);
    RenderOptions options;
    options.threads = threads;
    RenderStats stats;
    const Film film = prepared.render(base, options, &stats);
    const double rmse = compareBeauty(film, ref).rmse;
    mse[k] = rmse * rmse;
    rate[k] = double(w) * h * base.getInt("spp") / stats.seconds * 1e-6;
    std::printf("  %-11s RMSE %.5f, %.3f Msamples/s\n", names[k], rmse, rate[k]);
  }
  // A Sobol' sample is worth mse[0] / mse[1] independent ones at this error level.
  std::printf("  sobol: MSE ratio %.2f, so %.2f independent-equivalent Msamples/s\n",
              mse[0] / mse[1], rate[1] * mse[0] / mse[1]);
}

/// Forwards to an accelerator and sums the time spent in its batched queries (a wavefront
/// integrator's only queries): its share of the render is the traversal fraction, measured in
/// the render itself. Each batch is thousands of rays, so the clock reads cost nothing.
class BatchTimingAccelerator final : public Accelerator {
 public:
  explicit BatchTimingAccelerator(const Accelerator& inner) : inner_(inner) {}
  bool intersect(const Ray& ray, Hit& hit) const override { return inner_.intersect(ray, hit); }
  bool occluded(const Ray& ray) const override { return inner_.occluded(ray); }
  void allHits(const Ray& ray, std::vector<Hit>& hits) const override { inner_.allHits(ray, hits); }
  void intersectBatch(std::span<const Ray> rays, std::span<Hit> hits,
                      std::span<uint8_t> found) const override {
    const auto start = std::chrono::steady_clock::now();
    inner_.intersectBatch(rays, hits, found);
    add(closestNs, start);
  }
  void occludedBatch(std::span<const Ray> rays, std::span<uint8_t> blocked) const override {
    const auto start = std::chrono::steady_clock::now();
    inner_.occludedBatch(rays, blocked);
    add(shadowNs, start);
  }
  mutable std::atomic<int64_t> closestNs{0}, shadowNs{0};

 private:
  static void add(std::atomic<int64_t>& sum, std::chrono::steady_clock::time_point start) {
    sum += std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now() - start)
               .count();
  }
  const Accelerator& inner_;
};

/// One integrator's render, its CPU time and (wavefront) the time in batched traversal.
struct Measured {
  RenderStats stats;
  double cpu = 0, samples = 0, traversal = -1;
  double shadowShare = 0;  ///< the part of `traversal` spent on shadow rays
  double perCpuSecond() const { return samples / cpu * 1e-6; }
};

/// `accel`: the prepared scene's or another built over its scene (a batch mode).
Measured measure(const PreparedScene& prepared, const Accelerator& accel, RenderSettings settings,
                 const std::string& integrator, int size, int threads) {
  settings.set("integrator", integrator);
  BatchTimingAccelerator timed(accel);
  auto made = makeIntegrator(prepared.context(settings, timed));
  Film film(size, size);
  RenderOptions options;
  options.threads = threads;
  Measured m;
  const double cpuStart = cpuSeconds();
  m.stats = renderImage(*made, film, options);
  m.cpu = cpuSeconds() - cpuStart;
  m.samples = double(size) * size * settings.getInt("spp");
  const double batched = double(timed.closestNs + timed.shadowNs) * 1e-9;
  if (batched > 0) m.traversal = batched / (m.stats.seconds * threads);
  if (batched > 0) m.shadowShare = double(timed.shadowNs) * 1e-9 / batched;
  return m;
}

void print(const std::string& integrator, const Measured& m, int threads) {
  std::printf("  %s\n", integrator.c_str());
  std::printf("    time            %.2f s\n", m.stats.seconds);
  std::printf("    Msamples/s      %.3f\n", m.samples / m.stats.seconds * 1e-6);
  std::printf(
      "    CPU time        %.2f s: %.3f Msamples per CPU-second (x %d threads = %.3f "
      "Msamples/s on idle cores)\n",
      m.cpu, m.perCpuSecond(), threads, m.perCpuSecond() * threads);
  std::printf(
      "    Mrays/s         %.2f, %.2f Mrays per CPU-second (camera %.3fM, bounce %.3fM, "
      "shadow %.3fM)\n",
      m.stats.mraysPerSecond(), m.stats.rays.total() / m.cpu * 1e-6, m.stats.rays.cameraRays * 1e-6,
      m.stats.rays.secondaryRays * 1e-6, m.stats.rays.shadowRays * 1e-6);
  if (m.traversal >= 0)
    std::printf("    traversal       %.0f%% of the render (time in batched queries)\n",
                100 * m.traversal);
  if (m.stats.rays.simdVertices > 0)
    std::printf(
        "    SIMD shading    %.1f%% of the shaded vertices, %.0f%% of the traced segments "
        "(matte, glossy and delta stages)\n",
        100.0 * double(m.stats.rays.simdVertices) / double(m.stats.rays.shadedVertices),
        100.0 * double(m.stats.rays.simdVertices) /
            double(m.stats.rays.cameraRays + m.stats.rays.secondaryRays));
  std::printf("    NaN samples     %llu\n", (unsigned long long)m.stats.rays.nanSamples);
}

/// A scene from its file; one without lights (most glTF samples) gets a white sky, so that
/// paths bounce as under an environment rather than ending black.
Scene benchScene(const std::string& path) {
  Scene scene = loadGltf(path);
  bool lit = !scene.lights.empty();
  for (const Material& m : scene.materials) lit = lit || !isBlack(m.emissive);
  if (!lit) scene.environment.background = Color(1.0f);
  return scene;
}

/// The scalar path tracer's rays, recorded on a quarter of the pixels, then traced again with
/// nothing else: the share of its render that is traversal.
void replay(const Scene& scene, const Accelerator& accel, const RenderSettings& settings,
            int size) {
  RecordingAccelerator recorder(accel);
  const int small = std::max(16, size / 4);
  const PreparedScene prepared(scene, chooseCamera(scene, -1), {small, small}, accel);
  auto smallIntegrator = makeIntegrator(prepared.context(settings, recorder));
  Film smallFilm(small, small);
  RenderOptions one;
  one.threads = 1;
  renderImage(*smallIntegrator, smallFilm, one);
  // Timed again without the recorder's lock, for the share.
  RenderStats smallStats = renderImage(*prepared.integrator(settings), smallFilm, one);
  double closest = replaySeconds(accel, recorder.closest, false, 1);
  double shadowSeconds = replaySeconds(accel, recorder.shadow, true, 1);
  std::printf(
      "    replay          %.2f s render (1 thread, %dx%d): %.2f s closest hits "
      "(%.1f Mrays/s), %.2f s shadow rays (%.1f Mrays/s): traversal %.0f%%\n",
      smallStats.seconds, small, small, closest, recorder.closest.size() / closest * 1e-6,
      shadowSeconds, recorder.shadow.size() / shadowSeconds * 1e-6,
      100 * (closest + shadowSeconds) / smallStats.seconds);
}

int run(const std::string& path, const std::string& accelName, int threads, int size, int spp,
        bool replayRays, const std::string& sampler, bool error, bool batchModes) {
  Scene scene = benchScene(path);
  const PreparedScene prepared(scene, chooseCamera(scene, -1), {size, size}, accelName);
  const Accelerator& accel = prepared.accelerator();
  RenderSettings settings;
  settings.set("integrator", "path-scalar");  // the replay records the scalar driver's rays
  settings.set("spp", spp);
  settings.set("max-depth", 8);
  settings.set("sampler", sampler);
  std::printf("path tracing %s: %dx%d, %d spp, max depth 8, %d threads, %s sampler, %s\n",
              path.c_str(), size, size, spp, threads, sampler.c_str(), accelName.c_str());
  const Measured scalar = measure(prepared, accel, settings, "path-scalar", size, threads);
  print("path-scalar (one path at a time)", scalar, threads);
  if (replayRays) replay(scene, accel, settings, size);
  const Measured wave = measure(prepared, accel, settings, "path", size, threads);
  print("path (the wavefront driver, path-wavefront)", wave, threads);
  std::printf("  wavefront / scalar: %.2fx samples per CPU-second\n",
              wave.perCpuSecond() / scalar.perCpuSecond());
  if (batchModes) {
    // How the wavefront's batches are traced: per ray, or by the accelerator's batched ways.
    std::vector<std::pair<std::string, std::unique_ptr<Accelerator>>> modes;
    if (accelName == "embree") {
      modes.emplace_back("rtcIntersect1 loop", makeEmbreeAccelerator(scene, EmbreeBatch::kLoop));
      modes.emplace_back("rtcIntersect1M stream",
                         makeEmbreeAccelerator(scene, EmbreeBatch::kStream));
      modes.emplace_back("rtcIntersect8 packets",
                         makeEmbreeAccelerator(scene, EmbreeBatch::kPacket8));
    } else if (accelName == "bvh" || accelName == "bvh-gs") {
      for (BvhBatch batch : {BvhBatch::kLoop, BvhBatch::kPacket8, BvhBatch::kStream64}) {
        TwoLevelOptions options;
        if (accelName == "bvh-gs") options.build.builder = BvhBuilder::kGoldsmithSalmon;
        options.batch = batch;
        const int rays = bvhBatchRays(batch);
        modes.emplace_back(rays == 1 ? "single-ray loop" : std::to_string(rays) + "-ray groups",
                           makeTwoLevelAccelerator(scene, options));
      }
    }
    for (const auto& [name, a] : modes) {
      const Measured m = measure(prepared, *a, settings, "path-wavefront", size, threads);
      std::printf("  wavefront, %-26s %.3f Msamples per CPU-second (%.2fx scalar), traversal "
                  "%.0f%% (%.0f%% of it shadow rays)\n",
                  name.c_str(), m.perCpuSecond(), m.perCpuSecond() / scalar.perCpuSecond(),
                  100 * m.traversal, 100 * m.shadowShare);
    }
  }
  double raw = rawTraversalMrays(accel, scene.bounds(), threads);
  std::printf("  raw %-11s %.2f Mrays/s (random incoherent closest hits)\n", accelName.c_str(),
              raw);
  std::printf("  path / raw      %.2f, path-wavefront / raw %.2f\n",
              scalar.stats.mraysPerSecond() / raw, wave.stats.mraysPerSecond() / raw);
  const std::string refPath = path.substr(0, path.rfind('.')) + ".ref.exr";
  if (error) {
    RenderSettings at64 = settings;
    at64.set("spp", 64);
    equalError(scene, accel, refPath, at64, threads);
  }
  return 0;
}

int main(int argc, char** argv) {
  std::string path = std::string(TRAY_SOURCE_DIR) + "/../shared/reference/cornell-box.gltf";
  std::string accelName = "embree";
  int threads = 2, size = 512, spp = 64;
  bool replay = true, error = true, batchModes = false;
  std::string sampler = "independent";
  CLI::App app{"Path tracing throughput (Msamples/s, Mrays/s) against bare traversal"};
  app.add_option("scene", path, "glTF scene (default: the shared Cornell box)");
  app.add_option("threads", threads, "worker threads")->check(CLI::Range(1, 4096));
  app.add_option("size", size, "image width and height")->check(CLI::Range(1, 16384));
  app.add_option("spp", spp, "samples per pixel")->check(CLI::Range(1, 1 << 20));
  app.add_option("--accel", accelName, "accelerator: embree, bvh, bvh-gs, naive");
  app.add_option("--sampler", sampler, "random sequence of the throughput run: independent, sobol")
      ->check(CLI::IsMember(Sampler::names()));
  app.add_flag("!--no-replay", replay, "skip the replay of the path's rays (profiling runs)");
  app.add_flag("!--no-error", error,
               "skip the equal-error comparison (needs SCENE.ref.exr beside the scene)");
  app.add_flag("--batch-modes,--embree-modes", batchModes,
               "also time path-wavefront with each way the accelerator batches queries "
               "(embree: loop, stream, packets; bvh, bvh-gs: loop, 8-ray packets, 64-ray "
               "streams)");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(path, accelName, threads, size, spp, replay, sampler, error, batchModes);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "path_bench: %s\n", e.what());
    return 2;
  }
}

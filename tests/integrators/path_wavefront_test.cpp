// path-wavefront (what `path` runs) against the scalar path tracer it must equal
// (`path-scalar`). Both run PathEstimator over
// the same random numbers per pixel sample, and every bounce's rays meet the same
// accelerator queries, so the images are expected to be the same bits (tolerance 0); only a
// batched traversal that returned a different closest hit among equal-t candidates could make
// them differ, and the tests below would show it. docs/wavefront.md.
#include "integrators/path_wavefront.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <string>

#include "accel/registry.h"
#include "film/aov.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "tests/integrators/render_job.h"
#include "tests/scene_builder.h"
#include "textures/texture_sampler.h"

namespace tray {
namespace {

using test::differingValues;
using test::Job;
using test::Render;
using test::render;

const std::string kShared = TRAY_SHARED_DIR;

/// A scene from ../shared; one without lights gets a point light at the camera.
Scene sharedScene(const std::string& file) {
  Scene scene = loadGltf(kShared + "/" + file);
  if (!scene.lights.empty()) return scene;
  const Vec3 eye = chooseCamera(scene, -1).toWorld.point(Vec3(0.0f));
  const float d2 = lengthSquared(scene.bounds().center() - eye);
  scene.lights.push_back(test::pointLight(eye, Color(2.0f * std::max(d2, 1e-4f))));
  return scene;
}

const Scene& cornell() {
  static const Scene s = loadGltf(kShared + "/reference/cornell-box.gltf");
  return s;
}

/// Renders `job` with `path-scalar` and with the wavefront, expecting every value of the two
/// films (beauty, AOVs, Cryptomatte) and the ray counts equal; returns the wavefront's render.
Render expectWavefrontSameAsScalar(const Scene& scene, Job job) {
  job.integrator = "path-scalar";
  const Render scalar = render(scene, job);
  job.integrator = "path-wavefront";
  Render wave = render(scene, job);
  EXPECT_EQ(differingValues(scalar.film, wave.film), 0u);
  EXPECT_EQ(scalar.stats.rays.cameraRays, wave.stats.rays.cameraRays);
  EXPECT_EQ(scalar.stats.rays.secondaryRays, wave.stats.rays.secondaryRays);
  EXPECT_EQ(scalar.stats.rays.shadowRays, wave.stats.rays.shadowRays);
  return wave;
}

struct Case {
  const char* scene;  ///< under ../shared
  const char* accel;
  const char* sampler;
};

class SameAsScalar : public testing::TestWithParam<Case> {};

// Same random numbers per sample, same estimator: the same pixels, AOVs (the light-path
// layers among them) and Cryptomatte included, and the same ray counts.
TEST_P(SameAsScalar, SamePixelsAovsAndRayCounts) {
  const Case c = GetParam();
  const Scene scene = sharedScene(c.scene);
  Job job;
  job.accel = c.accel, job.sampler = c.sampler;
  job.aovs = AovSet::known();
  const Render wave = expectWavefrontSameAsScalar(scene, job);
  EXPECT_GT(wave.stats.rays.shadowRays, 0u);
  // The light-path layers were filled, not both left black: every scene has direct light.
  const int direct = wave.film.findLayer("diffuse_direct");
  ASSERT_GE(direct, 0);
  float peak = 0;
  for (int y = 0; y < job.size; ++y)
    for (int x = 0; x < job.size; ++x) peak = std::max(peak, wave.film.pixel(direct, x, y)[0]);
  EXPECT_GT(peak, 0.0f);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, SameAsScalar,
    testing::Values(Case{"reference/cornell-box.gltf", "embree", "sobol"},
                    Case{"reference/cornell-box.gltf", "embree", "independent"},
                    // The BVH's batches are its packet traversal (accel/bvh_batch.cpp).
                    Case{"reference/cornell-box.gltf", "bvh", "sobol"},
                    Case{"reference/furnace-sphere.gltf", "embree", "sobol"},
                    // Alpha-tested (MASK, BLEND) triangles: Embree's filter in a stream query.
                    Case{"gltf-features/AlphaBlendModeTest.glb", "embree", "sobol"},
                    Case{"gltf-features/AlphaBlendModeTest.glb", "bvh", "sobol"},
                    Case{"gltf-samples/TransmissionTest.glb", "embree", "sobol"}),
    [](const testing::TestParamInfo<Case>& info) {
      std::string s =
          std::string(info.param.scene) + "_" + info.param.accel + "_" + info.param.sampler;
      for (char& ch : s)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return s;
    });

// Textures read in their finest level only (LINEAR both ways, as the Mitsuba bench's scene
// has them): the wavefront prefetches each queue's texels ahead of its lookups
// (TextureSampler::prefetch), the scalar driver does not. A prefetch reads no value, so the
// pixels are the same.
TEST(PathWavefront, TexelPrefetchChangesNoPixel) {
  LoadOptions options;
  options.allowAnyPath = true;  // the bench scene names ../shared's assets
  const Scene scene =
      loadGltf(std::string(TRAY_SOURCE_DIR) + "/scenes/bench/heavy-helmets.gltf", options);
  int levelZeroOnly = 0;
  for (const Material& m : scene.materials)
    for (const TextureRef* ref :
         {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.emissiveTexture, &m.normalTexture})
      levelZeroOnly += ref->valid() && !TextureSampler::footprintMatters(*ref);
  ASSERT_GE(levelZeroOnly, 8) << "the helmet's and the bottle's textures, all prefetched";
  Job job;
  job.size = 32, job.spp = 2;
  job.aovs = AovSet::known();
  expectWavefrontSameAsScalar(scene, job);
}

// Motion blur: each camera ray's time travels with its path through Embree's packets (RTCRay8
// time) and the BVH's (per-ray instance transforms) as through the scalar queries, so a moving
// object changes nothing of the equality.
TEST(PathWavefront, MotionBlurredSameAsScalar) {
  Scene scene = cornell();
  Primitive& mover = scene.primitives.back();
  const Vec3 shift = 0.1f * (scene.bounds().hi - scene.bounds().lo);
  mover.motion = {mover.toWorld.m, Mat4::translate({shift.x, shift.y, 0}) * mover.toWorld.m};
  ASSERT_TRUE(scene.moving());
  for (const char* accel : {"embree", "bvh"}) {
    Job job;
    job.accel = accel;
    job.aovs = AovSet::known();
    const Render scalar = render(scene, job);
    job.integrator = "path-wavefront";
    const Render wave = render(scene, job);
    EXPECT_EQ(differingValues(scalar.film, wave.film), 0u) << accel;
    EXPECT_EQ(scalar.stats.rays.shadowRays, wave.stats.rays.shadowRays) << accel;
    job.integrator = "path-scalar";
    const Render still = render(cornell(), job);  // the motion shows
    EXPECT_GT(differingValues(still.film, scalar.film), 0u) << accel;
  }
}

// `path` runs the wavefront driver (issue 16: same pixels, faster on every bench scene);
// `path-scalar` keeps the one-path-at-a-time reference, and `path-wavefront` names the
// wavefront too. The renderer hands the wavefront a tile of pixels at once, the scalar one
// pixel at a time.
TEST(PathWavefront, PathRunsTheWavefrontDriver) {
  const Scene scene = cornell();
  auto batch = [&](const std::string& name) {
    RenderSettings settings;
    settings.set("integrator", name);
    const PreparedScene prepared(scene, chooseCamera(scene, -1), {8, 8});
    const RenderContext ctx = prepared.context(settings);
    return makeIntegrator(ctx)->pixelBatch();
  };
  EXPECT_GT(batch("path"), 1);
  EXPECT_EQ(batch("path"), batch("path-wavefront"));
  EXPECT_EQ(batch("path-scalar"), 1);
  Job job;
  const Render scalar = render(scene, job);
  job.integrator = "path";
  EXPECT_EQ(differingValues(scalar.film, render(scene, job).film), 0u);
}

// adaptive calls its inner integrator's Li sample by sample: under `--inner path` (the
// wavefront driver) the image must be the scalar driver's, bit for bit. It was not while Li
// ran a wave of one (18 of 4096 pixels differed: the caller's PrimaryHit was overwritten).
TEST(PathWavefront, AdaptiveInnerPathEqualsScalar) {
  const Scene scene = cornell();
  auto image = [&](const std::string& inner) {
    Job job;
    job.integrator = "adaptive", job.inner = inner, job.size = 32, job.spp = 4;
    return render(scene, job).film;
  };
  const Film scalar = image("path-scalar");
  EXPECT_EQ(differingValues(scalar, image("path")), 0u);
  EXPECT_EQ(differingValues(scalar, image("path-wavefront")), 0u);
  EXPECT_GT(differingValues(scalar, image("whitted")), 0u);  // the comparison can fail
}

// Independent seeds: two unbiased estimates of the same image, whose channel means agree
// within Monte Carlo error (4 standard errors, from the per-pixel spread).
TEST(PathWavefront, ChannelMeansWithinMonteCarloErrorOfScalar) {
  Job job;
  job.sampler = "independent", job.size = 32, job.spp = 16, job.seed = 1;
  const Render scalar = render(cornell(), job);
  job.integrator = "path-wavefront", job.seed = 2;
  const Render wave = render(cornell(), job);
  const size_t n = size_t(job.size) * job.size;
  for (int c = 0; c < 3; ++c) {
    double mean[2] = {0, 0}, sq[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      const Film& f = k == 0 ? scalar.film : wave.film;
      for (int y = 0; y < job.size; ++y)
        for (int x = 0; x < job.size; ++x) {
          const double v = f.pixel(Film::kBeauty, x, y)[c];
          mean[k] += v / n, sq[k] += v * v / n;
        }
    }
    // Each pixel mean is an independent estimate: the spread of pixel differences bounds the
    // error of the image means' difference (conservative: it includes the image's variation).
    const double var = (sq[0] - mean[0] * mean[0]) + (sq[1] - mean[1] * mean[1]);
    const double sigma = std::sqrt(var / n);
    EXPECT_NE(mean[0], mean[1]) << "the seeds gave the same image";
    EXPECT_LT(std::fabs(mean[0] - mean[1]), 4 * sigma) << "channel " << c;
  }
}

// Same pixels whatever the thread count and tile size (a tile is one batch of paths).
TEST(PathWavefront, DeterministicAcrossThreadsAndTiles) {
  Job job;
  job.integrator = "path-wavefront", job.size = 40;
  const Render one = render(cornell(), job);
  job.threads = 2, job.tileSize = 7;
  const Render two = render(cornell(), job);
  EXPECT_EQ(differingValues(one.film, two.film), 0u);
}

// Sample ranges (the farm's --sample-range) add up to the whole: sums of [0, 3) and [3, 8).
TEST(PathWavefront, SampleRangesAddUpToTheWhole) {
  Job job;
  job.integrator = "path-wavefront";
  RenderState whole, part;
  render(cornell(), job, &whole);
  job.samples = SampleRange{0, 3};
  render(cornell(), job, &part);
  RenderState rest;
  job.samples = SampleRange{3, 8};
  render(cornell(), job, &rest);
  for (size_t p = 0; p < whole.sums.size(); ++p) {
    PixelSums sum = part.sums[p];
    sum += rest.sums[p];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum.rgb[c], whole.sums[p].rgb[c], 1e-9) << p;
    EXPECT_EQ(sum.weight, whole.sums[p].weight);
  }
}

// A checkpoint's pixels are kept and the rest rendered: the resumed image equals the whole.
TEST(PathWavefront, ResumedFromCheckpointEqualsUninterrupted) {
  Job job;
  job.integrator = "path-wavefront";
  RenderState state;
  const Render whole = render(cornell(), job, &state);
  RenderState half = RenderState::empty(state.done.size());
  for (size_t p = 0; p < state.done.size(); p += 2) half.sums[p] = state.sums[p], half.done[p] = 1;
  const Render resumed = render(cornell(), job, &half);
  EXPECT_EQ(resumed.stats.pixelsDone, state.done.size());
  EXPECT_EQ(differingValues(whole.film, resumed.film), 0u);
}

/// Embree, raising `stop` during the render's first batched query (in its first wave): a
/// signal arriving mid-wave, at a point the test chooses.
class StoppingAccelerator final : public Accelerator {
 public:
  StoppingAccelerator(const Accelerator& inner, std::atomic<bool>& stop)
      : inner_(inner), stop_(stop) {}
  bool intersect(const Ray& r, Hit& h) const override { return inner_.intersect(r, h); }
  bool occluded(const Ray& r) const override { return inner_.occluded(r); }
  void intersectBatch(std::span<const Ray> rays, std::span<Hit> hits,
                      std::span<uint8_t> found) const override {
    stop_ = true;
    inner_.intersectBatch(rays, hits, found);
  }
  void allHits(const Ray& r, std::vector<Hit>& hits) const override { inner_.allHits(r, hits); }

 private:
  const Accelerator& inner_;
  std::atomic<bool>& stop_;
};

// A stop (SIGINT, SIGTERM) ends a batch between waves: its first wave (kPathWaveSize paths,
// 1024: three whole pixels of 300 samples, and part of a fourth) is finished, and only the pixels
// whose samples all came before the stop are written, with the uninterrupted render's values. (The
// wavefront used to check nothing within a batch: a render with hours of samples per batch
// ignored the signal; Farm.RealSignalsExit130And143WithThePartialImage waited on it.)
TEST(PathWavefront, StopBetweenWavesWritesOnlyWholePixels) {
  const Scene& scene = cornell();
  const PreparedScene prepared(scene, chooseCamera(scene, -1), {16, 16});
  RenderSettings settings;
  settings.set("integrator", "path");
  constexpr int kSpp = 300;
  static_assert(kPathWaveSize % kSpp != 0 && kPathWaveSize / kSpp >= 2);
  settings.set("spp", kSpp);
  auto renderWith = [&](const Accelerator& accel, const std::atomic<bool>* stop, Film& film) {
    auto integrator = makeIntegrator(prepared.context(settings, accel));
    RenderOptions options;
    options.threads = 1;
    options.stop = stop;
    RenderState state;
    RenderStats stats = renderImage(*integrator, film, state, options);
    return std::make_pair(stats, state);
  };
  std::atomic<bool> stop{false};
  const StoppingAccelerator stopping(prepared.accelerator(), stop);
  Film stopped(16, 16);
  const auto [stoppedStats, stoppedState] = renderWith(stopping, &stop, stopped);
  EXPECT_TRUE(stoppedStats.interrupted);
  const size_t wholePixels = kPathWaveSize / kSpp;
  EXPECT_EQ(stoppedStats.pixelsDone, wholePixels);
  Film whole(16, 16);
  const auto [wholeStats, wholeState] = renderWith(prepared.accelerator(), nullptr, whole);
  EXPECT_EQ(wholeStats.pixelsDone, 256u);
  for (size_t p = 0; p < 256; ++p) {
    EXPECT_EQ(stoppedState.done[p], p < wholePixels ? 1 : 0) << p;
    if (!stoppedState.done[p]) continue;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(stoppedState.sums[p].rgb[c], wholeState.sums[p].rgb[c]);
  }
}

}  // namespace
}  // namespace tray

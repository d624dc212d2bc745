// The frame-level hook (Integrator::rendersFrames, renderFrame; render/frame_renderer.h): a toy
// integrator that fills whole frames, registered here. The renderer gives it the film's
// rectangle of the image, writes what it returns (beauty, AOVs, Cryptomatte), honours
// --threads through its task arena, and refuses with one line what a frame cannot do.
#include "render/frame_renderer.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <string>

#include "core/error.h"
#include "integrators/registry.h"
#include "tests/error_of.h"
#include "tests/integrators/render_job.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

/// Each pixel's red is its image x, green its image y, blue the threads of the arena it ran
/// in; `frame-iterations` iterations, each marking the pixel once more (alpha).
class FrameToy final : public Integrator {
 public:
  explicit FrameToy(const RenderContext& ctx) : Integrator(ctx) {}
  Color Li(const Ray&, Sampler&, RayStats&, PrimaryHit*) const override {
    throw Error("frame-toy renders whole frames");
  }
  bool rendersFrames() const override { return true; }
  FrameResult renderFrame(const FrameTask& task, std::span<FramePixel> pixels) const override {
    FrameResult r;
    const int iterations = int(ctx_.settings.getInt("spp"));
    const double threads = tbb::this_task_arena::max_concurrency();
    for (int k = 0; k < iterations; ++k) {
      tbb::parallel_for(size_t(0), pixels.size(), [&](size_t p) {
        FramePixel& px = pixels[p];
        px.sums.rgb[0] = task.x0 + int(p % size_t(task.width));
        px.sums.rgb[1] = task.y0 + int(p / size_t(task.width));
        px.sums.rgb[2] = threads;
        px.sums.weight = 1;
        px.sums.alpha = (k + 1.0) / iterations;
        px.first.hit = true, px.first.depth = float(k + 1);
        ++px.samples;
      });
      ++r.iterations;
      if (task.onProgress) task.onProgress(double(k + 1) / iterations);
    }
    return r;
  }
};

void registerFrameToy() {
  static const bool once = [] {
    registerIntegrator({"frame-toy",
                        "a test frame integrator",
                        [](const RenderContext& ctx) -> std::unique_ptr<Integrator> {
                          return std::make_unique<FrameToy>(ctx);
                        },
                        {},
                        ""});
    return true;
  }();
  (void)once;
}

const Scene& plane() {
  static const Scene s = [] {
    Scene s;
    test::addMeshInstance(
        s, test::addMesh(s, test::quadMesh(1, test::addMaterial(s, test::diffuse(Color(0.5f))))),
        Mat4::identity());
    s.cameras.push_back(test::lookAt({0, 3, 0.1f}, {0, 0, 0}));
    s.finalize();
    return s;
  }();
  return s;
}

test::Job frameJob() {
  registerFrameToy();
  test::Job job;
  job.integrator = "frame-toy";
  job.spp = 3;
  job.size = 20;
  job.threads = 2;
  return job;
}

TEST(FrameRenderer, FillsTheRegionWithImageCoordinates) {
  test::Job job = frameJob();
  job.x0 = 5, job.y0 = 7, job.width = 6, job.height = 4;
  job.aovs = {"depth"};
  const test::Render r = test::render(plane(), job);
  ASSERT_EQ(r.film.width(), 6);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) {
      const float* p = r.film.pixel(Film::kBeauty, x, y);
      EXPECT_EQ(p[0], float(5 + x));
      EXPECT_EQ(p[1], float(7 + y));
      EXPECT_EQ(p[2], 2.0f);  // the arena of --threads 2
      EXPECT_EQ(p[3], 1.0f);  // alpha: the sums' coverage
      EXPECT_EQ(r.film.pixel(r.film.findLayer("Z"), x, y)[0], 3.0f);
    }
  EXPECT_EQ(r.stats.passes, 3);
  EXPECT_EQ(r.stats.pixelsDone, 24u);
  EXPECT_FALSE(r.stats.interrupted);
}

TEST(FrameRenderer, RefusesWhatAFrameCannotDo) {
  test::Job job = frameJob();
  job.samples = SampleRange{0, 2};
  EXPECT_NE(errorOf([&] { test::render(plane(), job); }).find("--sample-range"), std::string::npos);
  job = frameJob();
  SamplingPasses passes;
  passes.threshold = 0.1f;
  job.passes = passes;
  EXPECT_NE(errorOf([&] { test::render(plane(), job); }).find("--noise-threshold"),
            std::string::npos);
  job = frameJob();
  job.checkpointSeconds = 1;
  EXPECT_NE(errorOf([&] { test::render(plane(), job); }).find("--checkpoint"), std::string::npos);
  job = frameJob();
  job.aovs = {"diffuse_direct"};
  EXPECT_NE(errorOf([&] { test::render(plane(), job); }).find("light-path"), std::string::npos);
}

// A time limit alone is the integrator's to honour: it reaches the task (not refused).
TEST(FrameRenderer, TimeLimitReachesTheIntegrator) {
  test::Job job = frameJob();
  SamplingPasses passes;
  passes.timeLimit = 100;
  job.passes = passes;
  EXPECT_EQ(test::render(plane(), job).stats.passes, 3);
}

}  // namespace
}  // namespace tray

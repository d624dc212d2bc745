// Rendering in passes (render/pass_renderer.h): noise-driven adaptive sampling and time limits,
// on the Cornell box through the path tracer.
#include "render/pass_renderer.h"

#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <vector>

#include "gltf/gltf_loader.h"
#include "tests/integrators/render_job.h"

namespace tray {
namespace {

using test::differingValues;
using test::Job;
using test::Render;
using test::render;

const Scene& cornell() {
  static const Scene s = loadGltf(std::string(TRAY_SHARED_DIR) + "/reference/cornell-box.gltf");
  return s;
}

Job adaptiveJob(float threshold = 0.05f, int spp = 128) {
  Job job;
  job.integrator = "path";
  job.spp = spp;
  job.size = 24;
  job.aovs = {"samples"};
  SamplingPasses passes;
  passes.threshold = threshold;
  job.passes = passes;
  return job;
}

/// The samples layer's counts, row by row.
std::vector<int> counts(const Film& film) {
  const int layer = film.findLayer("samples");
  std::vector<int> out;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) out.push_back(int(film.pixel(layer, x, y)[0]));
  return out;
}

/// The counts a pixel can have after whole steps.
std::set<int> reachable(const SamplingPasses& p) {
  std::set<int> out;
  for (int n = 0, s; (s = nextStep(n, p)) > 0;) out.insert(n += s);
  return out;
}

double channelMean(const Film& film, int c) {
  double sum = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) sum += film.pixel(Film::kBeauty, x, y)[c];
  return sum / (double(film.width()) * film.height());
}

// Samples go where the noise is: some pixels stop early, some take the maximum, every count
// is whole steps, and the samples layer says it.
TEST(PassRenderer, NoiseThresholdStopsPixelsByTheirError) {
  const Job job = adaptiveJob(0.035f);
  const Render r = render(cornell(), job);
  const std::vector<int> n = counts(r.film);
  SamplingPasses p = *job.passes;
  p.maxSamples = job.spp;
  const std::set<int> whole = reachable(p);
  uint64_t sum = 0;
  for (int c : n) {
    EXPECT_TRUE(whole.count(c)) << c;
    sum += uint64_t(c);
  }
  EXPECT_EQ(*std::min_element(n.begin(), n.end()), 16);
  EXPECT_EQ(*std::max_element(n.begin(), n.end()), 128);
  EXPECT_LT(double(sum) / n.size(), 0.8 * job.spp);
  EXPECT_EQ(r.stats.samples, sum);
  EXPECT_EQ(r.stats.rays.cameraRays, sum);
  EXPECT_EQ(r.stats.pixelsDone, n.size());
  EXPECT_GT(r.stats.passes, 2);
}

// Decisions depend on pixel sums alone: any thread count and tile size give the same bits.
TEST(PassRenderer, SameImageForAnyThreadCountAndTileSize) {
  Job job = adaptiveJob();
  job.threads = 1;
  const Render one = render(cornell(), job);
  job.threads = 3, job.tileSize = 8;
  const Render three = render(cornell(), job);
  EXPECT_EQ(differingValues(one.film, three.film), 0u);
}

// Stopping on an estimate does not move the image: channel means within Monte Carlo error of
// a uniform render with every sample.
TEST(PassRenderer, AdaptiveMeansMatchUniform) {
  Job job = adaptiveJob(0.02f, 256);
  job.threads = 0;
  const Render adaptive = render(cornell(), job);
  job.passes.reset();
  const Render uniform = render(cornell(), job);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(channelMean(adaptive.film, c), channelMean(uniform.film, c),
                0.01 * channelMean(uniform.film, c))
        << c;
}

// The white furnace (a sphere of albedo 0.8 in a constant environment of 1): stopping on an
// estimate keeps the closed form, as uniform sampling does.
TEST(PassRenderer, FurnaceMeansMatchUniform) {
  static const Scene furnace =
      loadGltf(std::string(TRAY_SHARED_DIR) + "/reference/furnace-sphere.gltf");
  Job job = adaptiveJob(0.02f, 256);
  job.threads = 0, job.size = 32;
  const Render adaptive = render(furnace, job);
  job.passes.reset();
  const Render uniform = render(furnace, job);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(channelMean(adaptive.film, c), channelMean(uniform.film, c), 2e-3) << c;
  EXPECT_LT(adaptive.stats.samples, uint64_t(256) * 32 * 32);
}

// A region whose edges are multiples of 8 decides as the whole image does: its pixels are the
// whole render's, bit for bit.
TEST(PassRenderer, AlignedRegionHasTheWholeImagesPixels) {
  Job job = adaptiveJob();
  const Render whole = render(cornell(), job);
  job.x0 = 8, job.y0 = 16, job.width = 16, job.height = 8;
  const Render part = render(cornell(), job);
  for (size_t l = 0; l < part.film.layers().size(); ++l)
    for (int y = 0; y < job.height; ++y)
      for (int x = 0; x < job.width; ++x)
        for (size_t c = 0; c < part.film.layers()[l].channels.size(); ++c)
          ASSERT_EQ(part.film.pixel(int(l), x, y)[c],
                    whole.film.pixel(int(l), x + job.x0, y + job.y0)[c])
              << l << " " << x << " " << y;
}

// Every checkpoint, mid-pass ones with pixels still owed their step included, resumes to the
// uninterrupted render.
TEST(PassRenderer, EveryCheckpointResumesToTheUninterruptedRender) {
  Job job = adaptiveJob();
  job.threads = 2, job.tileSize = 8;
  std::vector<std::pair<Film, RenderState>> checkpoints;
  job.checkpointSeconds = 1e-9;
  job.onCheckpoint = [&](const Film& f, const RenderState& s) { checkpoints.emplace_back(f, s); };
  RenderState end;
  const Render whole = render(cornell(), job, &end);
  ASSERT_GT(checkpoints.size(), 4u);
  job.checkpointSeconds = 0, job.onCheckpoint = nullptr;
  size_t midPass = 0;
  for (size_t i = 0; i < checkpoints.size(); i += checkpoints.size() / 4) {
    auto [film, state] = checkpoints[i];
    EXPECT_EQ(state.pixelsDone(), 0u);
    midPass += std::any_of(state.progress.begin(), state.progress.end(),
                           [](const PixelProgress& g) { return g.pending; });
    const Render resumed = render(cornell(), job, &state, &film);
    EXPECT_EQ(differingValues(whole.film, resumed.film), 0u) << "checkpoint " << i;
    for (size_t p = 0; p < end.sums.size(); ++p)
      ASSERT_EQ(state.sums[p].rgb[0], end.sums[p].rgb[0]) << "checkpoint " << i << " pixel " << p;
  }
  EXPECT_GT(midPass, 0u);
}

// A signal stops the render between steps: no pixel is done, each keeps whole steps, and
// the progress resumes to the uninterrupted render.
TEST(PassRenderer, StopKeepsWholeStepsAndResumes) {
  Job job = adaptiveJob();
  job.threads = 1;
  const Render whole = render(cornell(), job);
  std::atomic<bool> stop{false};
  job.stop = &stop;
  int tiles = 0;
  job.checkpointSeconds = 1e-9;  // a hook after each tile: the 5th raises the stop
  job.onCheckpoint = [&](const Film&, const RenderState&) {
    if (++tiles == 5) stop = true;
  };
  RenderState state;
  const Render stopped = render(cornell(), job, &state);
  EXPECT_TRUE(stopped.stats.interrupted);
  EXPECT_EQ(state.pixelsDone(), 0u);
  SamplingPasses p = *job.passes;
  p.maxSamples = job.spp;
  const std::set<int> whole_steps = reachable(p);
  for (const PixelProgress& g : state.progress)
    EXPECT_TRUE(g.count == 0 || whole_steps.count(int(g.count))) << g.count;
  job.stop = nullptr, job.checkpointSeconds = 0, job.onCheckpoint = nullptr;
  const Render resumed = render(cornell(), job, &state, &stopped.film);
  EXPECT_EQ(differingValues(whole.film, resumed.film), 0u);
}

// The time limit ends the render after the first pass, every pixel with whole steps, and the
// render is complete (not interrupted).
TEST(PassRenderer, TimeLimitEndsWithWholeSteps) {
  Job job = adaptiveJob(0.0f, 1 << 16);
  job.passes->timeLimit = 0.3;
  job.threads = 2;
  const Render r = render(cornell(), job);
  EXPECT_TRUE(r.stats.timeLimitReached);
  EXPECT_FALSE(r.stats.interrupted);
  EXPECT_EQ(r.stats.pixelsDone, size_t(24 * 24));
  EXPECT_LT(r.stats.seconds, 10.0);
  SamplingPasses p = *job.passes;
  p.maxSamples = job.spp;
  const std::set<int> whole = reachable(p);
  for (int c : counts(r.film)) {
    EXPECT_GE(c, 16);
    EXPECT_LT(c, job.spp);
    EXPECT_TRUE(whole.count(c)) << c;
  }
}

// A sample range is a pass render of its own samples: counts from the range's size, and the
// sums of two parts' pixels add as uniform parts do.
TEST(PassRenderer, SampleRangePartsSpendTheirOwnSamples) {
  Job job = adaptiveJob(0.05f, 128);
  job.samples = SampleRange{64, 128};
  const Render part = render(cornell(), job);
  for (int c : counts(part.film)) {
    EXPECT_GE(c, 16);
    EXPECT_LE(c, 64);
  }
  EXPECT_EQ(part.stats.rays.cameraRays, part.stats.samples);
}

}  // namespace
}  // namespace tray

#include "core/pixel_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/error.h"
#include "core/sampler.h"
#include "tests/raster_function.h"

namespace tray {
namespace {

using namespace tray::test;
using Pattern = PixelSampler::Pattern;

TEST(PixelSampler, NamesResolve) {
  EXPECT_EQ(PixelSampler::parse("auto", 1), Pattern::kCenter);
  EXPECT_EQ(PixelSampler::parse("auto", 4), Pattern::kJitter);
  EXPECT_EQ(PixelSampler::parse("corners", 1), Pattern::kCorners);
  // With a stratifying sequence, auto takes its points at power-of-two counts (nets).
  EXPECT_EQ(PixelSampler::parse("auto", 64, true), Pattern::kSequence);
  EXPECT_EQ(PixelSampler::parse("auto", 48, true), Pattern::kJitter);
  EXPECT_EQ(PixelSampler::parse("auto", 64, false), Pattern::kJitter);
  EXPECT_EQ(PixelSampler::parse("auto", 1, true), Pattern::kCenter);
  EXPECT_EQ(PixelSampler::parse("sequence", 4), Pattern::kSequence);
  // A pixel that may stop after any sample (renders in passes) needs every prefix spread out:
  // auto takes the sequence at any count, the stratum-ordered patterns are refused.
  EXPECT_EQ(PixelSampler::parse("auto", 48, true, true), Pattern::kSequence);
  EXPECT_EQ(PixelSampler::parse("auto", 100, false, true), Pattern::kSequence);
  EXPECT_EQ(PixelSampler::parse("auto", 1, true, true), Pattern::kCenter);
  EXPECT_EQ(PixelSampler::parse("center", 8, true, true), Pattern::kCenter);
  for (const char* name : {"grid", "jitter", "corners"})
    EXPECT_THROW(PixelSampler::parse(name, 16, true, true), Error) << name;
  const PixelSampler seq(Pattern::kSequence, 5, 1.5f);
  EXPECT_EQ(seq.count(), 5);
  const Vec2 o = seq.offset(3, {0.25f, 0.75f});
  EXPECT_FLOAT_EQ(o.x, -0.75f);
  EXPECT_FLOAT_EQ(o.y, 0.75f);
  EXPECT_THROW(PixelSampler::parse("halton", 4), Error);
}

TEST(PixelSampler, CenterIsOneRayThroughTheCentre) {
  PixelSampler p(Pattern::kCenter, 16, 0.5f);
  ASSERT_EQ(p.count(), 1);
  Vec2 d = p.offset(0, {0.9f, 0.1f});
  EXPECT_EQ(d.x, 0.0f);
  EXPECT_EQ(d.y, 0.0f);
}

TEST(PixelSampler, GridPositionsAreExactStratumCentres) {
  for (float radius : {0.5f, 2.0f})
    for (int n : {1, 2, 3, 4, 8}) {
      // A non-square spp rounds down to the largest square grid.
      PixelSampler p(Pattern::kGrid, n * n + n, radius);
      ASSERT_EQ(p.count(), n * n);
      for (int i = 0; i < n * n; ++i) {
        Vec2 d = p.offset(i, {0.123f, 0.987f});  // u must not matter
        EXPECT_FLOAT_EQ(d.x, -radius + (i % n + 0.5f) * 2 * radius / n) << n << " " << i;
        EXPECT_FLOAT_EQ(d.y, -radius + (i / n + 0.5f) * 2 * radius / n) << n << " " << i;
      }
    }
}

TEST(PixelSampler, CornersModeTracesTheFourPixelCorners) {
  RasterWorld world;
  RenderSettings s;
  s.set("pixel-sampler", "corners");
  RasterIntegrator integrator(world.context(s, 8, 8), {[](float, float) { return 1.0f; }}, true);
  RayStats stats;
  PixelValue v = integrator.renderPixel(3, 5, stats);
  EXPECT_EQ(v.samples, 4u);
  EXPECT_EQ(stats.cameraRays, 4u);
  std::set<std::pair<float, float>> got;
  for (Vec2 p : integrator.positions) got.insert({p.x, p.y});
  std::set<std::pair<float, float>> corners{{3, 5}, {4, 5}, {3, 6}, {4, 6}};
  EXPECT_EQ(got, corners);
}

TEST(PixelSampler, JitterPutsOneSampleInEachStratum) {
  for (float radius : {0.5f, 1.5f})
    for (int n : {2, 3, 5}) {
      PixelSampler p(Pattern::kJitter, n * n + 2, radius);
      ASSERT_EQ(p.count(), n * n + 2);  // jitter keeps every requested sample
      std::vector<int> hits(size_t(n * n), 0);
      for (int i = 0; i < p.count(); ++i) {
        Sampler sampler(7, uint32_t(i), 3);
        Vec2 d = p.offset(i, sampler.next2D());
        ASSERT_LE(std::abs(d.x), radius);
        ASSERT_LE(std::abs(d.y), radius);
        if (i >= n * n) continue;  // the rest are uniform over the support
        int sx = std::min(n - 1, int((d.x + radius) / (2 * radius) * n));
        int sy = std::min(n - 1, int((d.y + radius) / (2 * radius) * n));
        ++hits[size_t(sy * n + sx)];
      }
      for (int h : hits) EXPECT_EQ(h, 1) << "n=" << n << " r=" << radius;
    }
}

TEST(PixelSampler, JitterVariesWithTheRandomNumbersGridDoesNot) {
  PixelSampler jitter(Pattern::kJitter, 4, 0.5f), grid(Pattern::kGrid, 4, 0.5f);
  EXPECT_NE(jitter.offset(1, {0.1f, 0.1f}).x, jitter.offset(1, {0.8f, 0.1f}).x);
  EXPECT_EQ(grid.offset(1, {0.1f, 0.1f}).x, grid.offset(1, {0.8f, 0.1f}).x);
}

}  // namespace
}  // namespace tray

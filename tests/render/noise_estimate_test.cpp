// The pieces of noise-driven adaptive sampling that decide (render/noise_estimate.h).
#include "render/noise_estimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace tray {
namespace {

PixelSums sums(double r, double g, double b, double weight) {
  PixelSums s;
  s.rgb[0] = r * weight, s.rgb[1] = g * weight, s.rgb[2] = b * weight, s.weight = weight;
  return s;
}

// The difference of the mean and the earlier mean, relative to the value as relMSE weighs
// error (d / sqrt(mean^2 + 0.01), RMS over R, G, B), scaled to the whole mean's error by
// sqrt(m / (n - m)): 1 when the earlier mean holds half of the samples.
TEST(NoiseEstimate, ErrorIsTheDifferenceWithTheEarlierMeanRelativeToTheValue) {
  EXPECT_EQ(pixelError(sums(1, 2, 3, 16), sums(1, 2, 3, 8), 16, 8), 0.0f);
  const double half = std::sqrt((0.25 / 1.01 + 0.25 / 1.01) / 3);
  EXPECT_NEAR(pixelError(sums(1, 1, 2, 16), sums(1.5, 0.5, 2, 8), 16, 8), half, 1e-6);
  // The earlier mean holds 16 of 24 samples: the difference is sqrt(2) times less noisy.
  EXPECT_NEAR(pixelError(sums(1, 1, 2, 24), sums(1.5, 0.5, 2, 16), 24, 16), half * std::sqrt(2.0),
              1e-6);
  // The same difference on a value 10x brighter is 10x smaller (relative); on black it is
  // absolute over 0.1 (the floor), finite.
  EXPECT_NEAR(pixelError(sums(10, 10, 20, 16), sums(15, 5, 20, 8), 16, 8),
              std::sqrt((25 / 100.01 + 25 / 100.01) / 3), 1e-6);
  EXPECT_NEAR(pixelError(sums(0, 0, 0, 4), sums(0.001, 0, 0, 2), 4, 2), std::sqrt(1e-4 / 3), 1e-7);
  // --noise-metric absolute: the difference in radiance units, whatever the value.
  EXPECT_NEAR(pixelError(sums(10, 10, 20, 16), sums(15, 5, 20, 8), 16, 8, true),
              std::sqrt((25.0 + 25.0) / 3), 1e-5);
  EXPECT_NEAR(pixelError(sums(1, 1, 2, 16), sums(1.5, 0.5, 2, 8), 16, 8, true),
              std::sqrt((0.25 + 0.25) / 3), 1e-6);
  // No estimate: no earlier samples, no new ones, or no weight.
  EXPECT_TRUE(std::isinf(pixelError(sums(1, 1, 1, 4), sums(1, 1, 1, 4), 1, 0)));
  EXPECT_TRUE(std::isinf(pixelError(sums(1, 1, 1, 4), sums(1, 1, 1, 4), 4, 4)));
  EXPECT_TRUE(std::isinf(pixelError(sums(1, 1, 1, 4), PixelSums{}, 4, 2)));
}

// The options reach the passes: none without --noise-threshold or --time-limit; the
// threshold, the minimum and each rule otherwise (defaults: mse, relative, neighbours).
TEST(NoiseEstimate, SettingsGiveThePasses) {
  RenderSettings settings;
  EXPECT_FALSE(samplingPassesOf(settings).has_value());
  settings.set("noise-threshold", 0.02f);
  std::optional<SamplingPasses> p = samplingPassesOf(settings);
  ASSERT_TRUE(p.has_value());
  EXPECT_FLOAT_EQ(p->threshold, 0.02f);
  EXPECT_EQ(p->minSamples, 16);
  EXPECT_FALSE(p->evenError);
  EXPECT_FALSE(p->absoluteError);
  EXPECT_EQ(p->decision, SamplingPasses::Decision::kWide);  // the default
  settings.set("noise-metric", std::string("absolute"));
  settings.set("noise-decision", std::string("pixel"));
  settings.set("noise-rule", std::string("even"));
  settings.set("min-spp", 8);
  p = samplingPassesOf(settings);
  ASSERT_TRUE(p.has_value());
  EXPECT_TRUE(p->absoluteError);
  EXPECT_EQ(p->decision, SamplingPasses::Decision::kPixel);
  EXPECT_TRUE(p->evenError);
  EXPECT_EQ(p->minSamples, 8);
  settings.set("noise-decision", std::string("max"));
  EXPECT_EQ(samplingPassesOf(settings)->decision, SamplingPasses::Decision::kMax);
  settings.set("noise-decision", std::string("wide"));
  EXPECT_EQ(samplingPassesOf(settings)->decision, SamplingPasses::Decision::kWide);
  settings.set("noise-decision", std::string("neighbours"));
  EXPECT_EQ(samplingPassesOf(settings)->decision, SamplingPasses::Decision::kNeighbours);
}

// The earlier look of each count in the sequence: half of the first step, then the look before.
TEST(NoiseEstimate, EarlierCountIsTheLookBefore) {
  SamplingPasses p;
  p.minSamples = 16, p.maxSamples = 100;
  EXPECT_EQ(earlierCount(16, p), 8);
  EXPECT_EQ(earlierCount(24, p), 16);
  EXPECT_EQ(earlierCount(32, p), 24);
  EXPECT_EQ(earlierCount(96, p), 64);
  EXPECT_EQ(earlierCount(100, p), 96);  // the step cut at the maximum
  p.minSamples = 1;
  EXPECT_EQ(earlierCount(1, p), 0);
  EXPECT_EQ(earlierCount(2, p), 1);
}

// mse: the stopping error grows as sqrt(count / minSamples); even: the threshold everywhere.
TEST(NoiseEstimate, StoppingErrorOfEachRule) {
  SamplingPasses p;
  p.threshold = 0.1f, p.minSamples = 16;
  EXPECT_FLOAT_EQ(stoppingError(16, p), 0.1f);
  EXPECT_FLOAT_EQ(stoppingError(64, p), 0.2f);
  EXPECT_FLOAT_EQ(stoppingError(1024, p), 0.8f);
  p.evenError = true;
  EXPECT_FLOAT_EQ(stoppingError(64, p), 0.1f);
  // A pixel of 64 samples at error 0.15 stops under mse, goes on under even.
  const std::vector<float> error(4, 0.15f);
  const std::vector<uint32_t> count(4, 64);
  std::vector<uint8_t> more(4);
  p.maxSamples = 1024;
  decideBlock(error, count, 2, 2, p, more);
  EXPECT_EQ(more, (std::vector<uint8_t>{1, 1, 1, 1}));
  p.evenError = false;
  decideBlock(error, count, 2, 2, p, more);
  EXPECT_EQ(more, (std::vector<uint8_t>{0, 0, 0, 0}));
}

// Two looks per doubling, every step a power of two and aligned (a run of Sobol' points),
// the last step cut at the maximum.
TEST(NoiseEstimate, StepsDoubleInTwoLooksAndStopAtTheMaximum) {
  SamplingPasses p;
  p.minSamples = 16, p.maxSamples = 100;
  std::vector<int> counts;
  for (int n = 0, s; (s = nextStep(n, p)) > 0; n += s) {
    EXPECT_EQ(n % s == 0 || n + s == p.maxSamples, true) << n << " + " << s;
    counts.push_back(n + s);
  }
  EXPECT_EQ(counts, (std::vector<int>{16, 24, 32, 48, 64, 96, 100}));
  p.minSamples = 1, p.maxSamples = 6;
  counts.clear();
  for (int n = 0, s; (s = nextStep(n, p)) > 0; n += s) counts.push_back(n + s);
  EXPECT_EQ(counts, (std::vector<int>{1, 2, 3, 4, 6}));
  p.minSamples = 64, p.maxSamples = 8;  // the minimum never passes the maximum
  EXPECT_EQ(nextStep(0, p), 8);
  EXPECT_EQ(nextStep(8, p), 0);
}

/// The 4x3 block of the two tests below: threshold 0.1, minimum 16, maximum 256, every pixel
/// at 32 samples (mse: stopping error 0.1 sqrt(2) = 0.141) and error 0.01 but (3, 2) at 1.0.
struct Block {
  static constexpr int w = 4, h = 3;
  SamplingPasses passes;
  std::vector<float> error = std::vector<float>(w * h, 0.01f);
  std::vector<uint32_t> count = std::vector<uint32_t>(w * h, 32);
  std::vector<uint8_t> more = std::vector<uint8_t>(w * h);

  explicit Block(SamplingPasses::Decision decision) {
    passes.threshold = 0.1f, passes.minSamples = 16, passes.maxSamples = 256;
    passes.decision = decision;
    error[2 * w + 3] = 1.0f;
  }
  /// decideBlock over the block's errors (or `errors`) and counts, into `more`.
  void decide() { decide(error); }
  void decide(const std::vector<float>& errors) { decideBlock(errors, count, w, h, passes, more); }
};

// A pixel's own error is not read (tests/render/adaptive_bias_test.cpp says why): the noisy
// pixel at (3, 2) stops among quiet neighbours, and keeps going those of its neighbours whose
// mean neighbour error it lifts past the limit, (3, 1) and (2, 2) (mean 0.208 over 5), not
// (2, 1) (0.134 over 8); a quiet pixel amid noisy ones goes on. A pixel below the minimum goes
// on whatever the errors, one at the maximum stops; a neighbour without an estimate (NaN,
// infinite) keeps a pixel going; a pixel with no neighbour goes on to the maximum; threshold
// 0: only the maximum stops.
TEST(NoiseEstimate, ABlockDecidesFromEachPixelsNeighbours) {
  Block b(SamplingPasses::Decision::kNeighbours);
  const int w = Block::w, h = Block::h;
  b.decide();
  for (int i = 0; i < w * h; ++i) EXPECT_EQ(b.more[i], i == 1 * w + 3 || i == 2 * w + 2) << i;
  std::vector<float> noisy(w * h, 0.5f);
  noisy[1 * w + 1] = 0.0f;  // halves that agree by chance
  b.decide(noisy);
  EXPECT_EQ(b.more[1 * w + 1], 1);
  b.count[0] = 8;            // below the minimum
  b.count[1 * w + 3] = 256;  // at the maximum: it stops
  b.error[0] = 0.0f;
  b.decide();
  EXPECT_EQ(b.more[0], 1);
  EXPECT_EQ(b.more[1 * w + 3], 0);
  b.error[5] = std::nanf("");  // no estimate: its neighbours go on
  b.decide();
  EXPECT_EQ(b.more[4], 1);
  EXPECT_EQ(b.more[6], 1);
  EXPECT_EQ(b.more[5], 0);
  b.error[5] = std::numeric_limits<float>::infinity();
  b.decide();
  EXPECT_EQ(b.more[10], 1);
  b.passes.threshold = 0;
  b.decide();
  for (int i = 0; i < w * h; ++i) EXPECT_EQ(b.more[i], i == 1 * w + 3 ? 0 : 1) << i;
  // A block of one pixel has no neighbour to decide from: it goes on.
  b.passes.threshold = 0.1f;
  decideBlock(std::vector<float>{0.0f}, std::vector<uint32_t>{32}, 1, 1, b.passes, b.more);
  EXPECT_EQ(b.more[0], 1);
}

// --noise-decision pixel: the pixel's own error also decides, and the 3x3 mean with itself.
// The noisy pixel of the block goes on, as do those of its neighbours whose mean with it
// passes the limit ((3, 1) and (2, 2): (0.05 + 1) / 6 = 0.175; (2, 1): 1.08 / 9 = 0.12, no);
// a quiet pixel amid noisy ones goes on; a pixel with no estimate goes on.
TEST(NoiseEstimate, PixelDecisionAlsoReadsThePixelsOwnError) {
  Block b(SamplingPasses::Decision::kPixel);
  const int w = Block::w, h = Block::h;
  b.decide();
  for (int i = 0; i < w * h; ++i)
    EXPECT_EQ(b.more[i], i == 2 * w + 3 || i == 1 * w + 3 || i == 2 * w + 2) << i;
  std::vector<float> noisy(w * h, 0.5f);
  noisy[1 * w + 1] = 0.0f;
  b.decide(noisy);
  EXPECT_EQ(b.more[1 * w + 1], 1);
  b.error[5] = std::nanf("");
  b.decide();
  EXPECT_EQ(b.more[5], 1);
  decideBlock(std::vector<float>{0.0f}, std::vector<uint32_t>{32}, 1, 1, b.passes, b.more);
  EXPECT_EQ(b.more[0], 0);
}

// --noise-decision max: the largest of the neighbours' errors decides. Every neighbour of the
// noisy pixel at (3, 2) goes on, (2, 1) too (its mean, 0.134, is below the limit; its largest
// 1.0 is not); the noisy pixel itself stops among quiet neighbours, as with the mean.
TEST(NoiseEstimate, MaxDecisionReadsTheLargestNeighbourError) {
  Block b(SamplingPasses::Decision::kMax);
  const int w = Block::w, h = Block::h;
  b.decide();
  for (int i = 0; i < w * h; ++i)
    EXPECT_EQ(b.more[i], i == 1 * w + 3 || i == 2 * w + 2 || i == 1 * w + 2) << i;
  b.error[5] = std::numeric_limits<float>::infinity();  // no estimate: its neighbours go on
  b.decide();
  EXPECT_EQ(b.more[0], 1);
  EXPECT_EQ(b.more[5], 0);
}

// --noise-decision wide: the RMS error of the 24 others of the 5x5 (inside the block). The
// noisy pixel at (3, 2) keeps every pixel within two of it going whose RMS passes the limit:
// (1, 0) sees 1.0 among 11 others (RMS 0.30), (0, 0) does not see it (0.01); the noisy pixel
// itself stops among quiet ones.
TEST(NoiseEstimate, WideDecisionReadsTheRmsOfThe5x5) {
  Block b(SamplingPasses::Decision::kWide);
  const int w = Block::w, h = Block::h;
  b.decide();
  for (int i = 0; i < w * h; ++i) EXPECT_EQ(b.more[i], i % w >= 1 && i != 2 * w + 3) << i;
}

// A whole image decides block by block: each 8x8 block of an 11 x 10 image (the last ones
// clipped) from its own pixels alone, as decideBlock on that block; a pixel on a block's edge
// does not see the next block's noise.
TEST(NoiseEstimate, AnImageDecidesInItsBlocks) {
  const int w = 11, h = 10;
  SamplingPasses passes;
  passes.threshold = 0.1f, passes.minSamples = 16, passes.maxSamples = 256;
  std::vector<float> error(w * h, 0.01f);
  error[3 * w + 8] = 1.0f;  // noisy, just inside the second block column
  error[9 * w + 2] = 1.0f;  // noisy, in the second block row
  const std::vector<uint32_t> count(w * h, 32);
  std::vector<uint8_t> more(w * h, 7);
  EXPECT_TRUE(decideImage(error, count, w, h, passes, more));
  for (int by = 0; by < h; by += kNoiseBlock)
    for (int bx = 0; bx < w; bx += kNoiseBlock) {
      const int bw = std::min(kNoiseBlock, w - bx), bh = std::min(kNoiseBlock, h - by);
      std::vector<float> e;
      std::vector<uint32_t> n;
      for (int y = by; y < by + bh; ++y)
        for (int x = bx; x < bx + bw; ++x) e.push_back(error[y * w + x]), n.push_back(32);
      std::vector<uint8_t> expected(size_t(bw) * bh);
      decideBlock(e, n, bw, bh, passes, expected);
      for (int i = 0; i < bw * bh; ++i)
        EXPECT_EQ(more[(by + i / bw) * w + bx + i % bw], expected[i])
            << bx << "," << by << ":" << i;
    }
  EXPECT_EQ(more[3 * w + 7], 0);  // left of the noisy pixel, in the first block: it stops
  EXPECT_EQ(more[3 * w + 9], 1);  // right of it, in its block: it goes on
  std::fill(error.begin(), error.end(), 0.0f);
  EXPECT_FALSE(decideImage(error, count, w, h, passes, more));
}

}  // namespace
}  // namespace tray

// Stopping a pixel on its own samples biases its mean (Kirk & Arvo 1991, "Unbiased sampling
// techniques for image synthesis"): the failure, then the fix. A simulated image whose every
// pixel has the same heavy-tailed samples (a rare bright path: 20 with probability 0.05, else
// 0; mean 1, as a pixel that sometimes finds a small light) goes through the pass loop of
// render/pass_renderer.cpp with the real steps, error estimate and block decision
// (render/noise_estimate.h). With --noise-decision pixel (the pixel's own error or its 3x3
// neighbourhood's mean, itself included: TRay's only rule before, and Cycles' way) pixels
// whose samples came out low stop more often: the mean is measurably dark. The default, which
// reads the neighbours' errors only, gives means within Monte Carlo error of the truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "render/noise_estimate.h"

namespace tray {
namespace {

constexpr int kSide = 128;  // 16x16 blocks of 8x8 pixels
constexpr double kBright = 20, kChance = 0.05;

struct Outcome {
  double mean = 0, samplesPerPixel = 0, standardError = 0;
};

/// The image's mean after adaptive passes: each pixel draws from its own random stream, in
/// steps, and each 8x8 block decides from its pixels' errors, as the pass renderer does;
/// `decision` as --noise-decision.
Outcome simulate(SamplingPasses::Decision decision, uint64_t seed) {
  SamplingPasses passes;
  passes.threshold = 0.3f, passes.minSamples = 16, passes.maxSamples = 256;
  passes.decision = decision;
  const int pixels = kSide * kSide;
  std::vector<std::mt19937_64> rng;
  for (int p = 0; p < pixels; ++p) rng.emplace_back(seed * 1000003u + uint64_t(p));
  std::bernoulli_distribution bright(kChance);
  std::vector<std::vector<double>> prefix(pixels, std::vector<double>{0.0});  // running sums
  std::vector<uint8_t> pending(pixels, 1);
  for (bool any = true; any;) {
    for (int p = 0; p < pixels; ++p) {
      if (!pending[p]) continue;
      const int n = int(prefix[p].size()) - 1;
      for (int s = nextStep(n, passes); s > 0; --s)
        prefix[p].push_back(prefix[p].back() + (bright(rng[p]) ? kBright : 0.0));
    }
    any = false;
    for (int by = 0; by < kSide; by += kNoiseBlock)
      for (int bx = 0; bx < kSide; bx += kNoiseBlock) {
        std::vector<float> error;
        std::vector<uint32_t> count;
        std::vector<uint8_t> more(kNoiseBlock * kNoiseBlock);
        for (int y = by; y < by + kNoiseBlock; ++y)
          for (int x = bx; x < bx + kNoiseBlock; ++x) {
            const std::vector<double>& sums = prefix[y * kSide + x];
            const int n = int(sums.size()) - 1, m = earlierCount(n, passes);
            PixelSums all, earlier;
            all.rgb[0] = all.rgb[1] = all.rgb[2] = sums[n], all.weight = n;
            earlier.rgb[0] = earlier.rgb[1] = earlier.rgb[2] = sums[m], earlier.weight = m;
            error.push_back(pixelError(all, earlier, n, m));
            count.push_back(uint32_t(n));
          }
        decideBlock(error, count, kNoiseBlock, kNoiseBlock, passes, more);
        for (int i = 0; i < kNoiseBlock * kNoiseBlock; ++i) {
          pending[(by + i / kNoiseBlock) * kSide + bx + i % kNoiseBlock] = more[i];
          any = any || more[i];
        }
      }
  }
  Outcome o;
  double variance = 0;  // of the image mean: sum over pixels of var(sample) / n / pixels^2
  const double sampleVariance = kBright * kBright * kChance * (1 - kChance);
  for (const std::vector<double>& sums : prefix) {
    const double n = double(sums.size() - 1);
    o.mean += sums.back() / n / pixels;
    o.samplesPerPixel += n / pixels;
    variance += sampleVariance / n / (double(pixels) * pixels);
  }
  o.standardError = std::sqrt(variance);
  return o;
}

TEST(AdaptiveBias, PixelDecisionDarkensNeighbourDecisionDoesNot) {
  double before = 0, after = 0, errorBefore = 0, errorAfter = 0;
  const int runs = 4;
  for (uint64_t seed = 1; seed <= runs; ++seed) {
    const Outcome old = simulate(SamplingPasses::Decision::kPixel, seed);
    const Outcome now = simulate(SamplingPasses::Decision::kNeighbours, seed);
    std::printf("seed %d: own error mean %.4f (%.1f spp), neighbours %.4f (%.1f spp), +-%.4f\n",
                int(seed), old.mean, old.samplesPerPixel, now.mean, now.samplesPerPixel,
                now.standardError);
    before += old.mean / runs, after += now.mean / runs;
    errorBefore += old.standardError * old.standardError / (runs * runs);
    errorAfter += now.standardError * now.standardError / (runs * runs);
    // Both rules spend samples where the noise is: neither is uniform sampling.
    EXPECT_LT(now.samplesPerPixel, 0.6 * 256);
  }
  // The failure: deciding on the pixel's own error darkens the mean by many standard errors.
  EXPECT_LT(before, 1.0 - 6 * std::sqrt(errorBefore));
  // The fix: within 4 standard errors of the truth.
  EXPECT_NEAR(after, 1.0, 4 * std::sqrt(errorAfter));
}

// The other unbiased decisions read only neighbours' errors too: --noise-decision max (their
// largest: more samples than the default) and wide (the RMS over the 24 others of the 5x5).
// Their means are as unbiased as the default's.
TEST(AdaptiveBias, MaxAndWideDecisionsAreUnbiased) {
  using D = SamplingPasses::Decision;
  const int runs = 4;
  double defaultSpp = 0;
  for (uint64_t seed = 1; seed <= runs; ++seed)
    defaultSpp += simulate(D::kNeighbours, seed).samplesPerPixel / runs;
  for (D decision : {D::kMax, D::kWide}) {
    double mean = 0, variance = 0, spp = 0;
    for (uint64_t seed = 1; seed <= runs; ++seed) {
      const Outcome o = simulate(decision, seed);
      std::printf("%s, seed %d: %.4f (%.1f spp), +-%.4f\n",
                  decision == D::kMax ? "max" : "wide", int(seed), o.mean, o.samplesPerPixel,
                  o.standardError);
      mean += o.mean / runs, spp += o.samplesPerPixel / runs;
      variance += o.standardError * o.standardError / (runs * runs);
    }
    EXPECT_NEAR(mean, 1.0, 4 * std::sqrt(variance));
    EXPECT_LT(spp, 0.9 * 256);  // still adaptive
    // The largest error is above the mean, and so is the RMS: more samples than the default.
    EXPECT_GT(spp, defaultSpp);
  }
}

}  // namespace
}  // namespace tray

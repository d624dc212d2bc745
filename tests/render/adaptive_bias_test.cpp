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
  double sppCheap = 0, sppDear = 0;  ///< samples per pixel of the left and right halves
};

/// --noise-cost rays in the simulation: a sample's rays, longer for the paths that find the
/// light (the cost is not independent of the value) and 6 more on the right half of the image.
double raysOf(bool brightSample, int x) {
  return (brightSample ? 12.0 : 2.0) + (x < kSide / 2 ? 0.0 : 6.0);
}

/// The image's mean after adaptive passes: each pixel draws from its own random stream, in
/// steps, and each 8x8 block decides from its pixels' errors, as the pass renderer does;
/// `decision` as --noise-decision, `weighCost` as --noise-cost rays (raysOf).
Outcome simulate(SamplingPasses::Decision decision, uint64_t seed, bool weighCost = false) {
  SamplingPasses passes;
  passes.threshold = 0.3f, passes.minSamples = 16, passes.maxSamples = 256;
  passes.decision = decision, passes.weighCost = weighCost;
  const int pixels = kSide * kSide;
  std::vector<std::mt19937_64> rng;
  for (int p = 0; p < pixels; ++p) rng.emplace_back(seed * 1000003u + uint64_t(p));
  std::bernoulli_distribution bright(kChance);
  std::vector<std::vector<double>> prefix(pixels, std::vector<double>{0.0});  // running sums
  std::vector<double> rays(pixels, 0.0);
  std::vector<uint8_t> pending(pixels, 1);
  for (bool any = true; any;) {
    for (int p = 0; p < pixels; ++p) {
      if (!pending[p]) continue;
      const int n = int(prefix[p].size()) - 1;
      for (int s = nextStep(n, passes); s > 0; --s) {
        const bool hit = bright(rng[p]);
        prefix[p].push_back(prefix[p].back() + (hit ? kBright : 0.0));
        rays[p] += raysOf(hit, p % kSide);
      }
    }
    any = false;
    for (int by = 0; by < kSide; by += kNoiseBlock)
      for (int bx = 0; bx < kSide; bx += kNoiseBlock) {
        std::vector<float> error, cost;
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
            cost.push_back(float(rays[y * kSide + x] / n));
          }
        decideBlock(error, count, kNoiseBlock, kNoiseBlock, passes, more, cost);
        for (int i = 0; i < kNoiseBlock * kNoiseBlock; ++i) {
          pending[(by + i / kNoiseBlock) * kSide + bx + i % kNoiseBlock] = more[i];
          any = any || more[i];
        }
      }
  }
  Outcome o;
  double variance = 0;  // of the image mean: sum over pixels of var(sample) / n / pixels^2
  const double sampleVariance = kBright * kBright * kChance * (1 - kChance);
  for (int p = 0; p < pixels; ++p) {
    const std::vector<double>& sums = prefix[p];
    const double n = double(sums.size() - 1);
    o.mean += sums.back() / n / pixels;
    o.samplesPerPixel += n / pixels;
    (p % kSide < kSide / 2 ? o.sppCheap : o.sppDear) += 2 * n / pixels;
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

// --noise-cost rays weighs each pixel's stopping error by its neighbours' rays per sample, not
// its own: a pixel's own cost here is high exactly when it found the bright samples (their
// paths are longer), so its own cost would stop it more often after bright samples, the bias
// of the pixel decision turned bright. With the wide decision the mean stays within Monte
// Carlo error of the truth (24 seeds: 1.0010 +- 0.0009), and the samples move from the dear
// half to the cheap half. (With the default decision the mean over 24 seeds is 0.9917 +-
// 0.0011, and so is the unweighed rule's where it takes as few samples: 0.9832 +- 0.0013 at
// threshold 0.45, 33 spp; its residual bias at low counts, docs/bench/adaptive-cost-2026-12-07.md.)
TEST(AdaptiveBias, CostWeighingFromTheNeighboursIsUnbiasedWithTheWideDecision) {
  const int runs = 8;
  double mean = 0, variance = 0, cheap = 0, dear = 0, cheapBlind = 0, dearBlind = 0;
  for (uint64_t seed = 1; seed <= runs; ++seed) {
    const SamplingPasses::Decision wide = SamplingPasses::Decision::kWide;
    const Outcome o = simulate(wide, seed, true), blind = simulate(wide, seed);
    std::printf("seed %d: %.4f (%.1f spp: %.1f cheap, %.1f dear; without cost %.1f, %.1f), "
                "+-%.4f\n",
                int(seed), o.mean, o.samplesPerPixel, o.sppCheap, o.sppDear, blind.sppCheap,
                blind.sppDear, o.standardError);
    mean += o.mean / runs;
    variance += o.standardError * o.standardError / (runs * runs);
    cheap += o.sppCheap / runs, dear += o.sppDear / runs;
    cheapBlind += blind.sppCheap / runs, dearBlind += blind.sppDear / runs;
  }
  EXPECT_NEAR(mean, 1.0, 4 * std::sqrt(variance));
  // Without cost both halves take the same samples (within noise); with it the cheap half
  // takes more than it did and than the dear half.
  EXPECT_NEAR(cheapBlind / dearBlind, 1.0, 0.05);
  EXPECT_GT(cheap, 1.5 * dear);
  EXPECT_GT(cheap, cheapBlind);
}

}  // namespace
}  // namespace tray

// Stopping a pixel on its own samples biases its mean (Kirk & Arvo 1991, "Unbiased sampling
// techniques for image synthesis"): the failure, then the fix. A simulated image whose every
// pixel has the same heavy-tailed samples (a rare bright path: 20 with probability 0.05, else
// 0; mean 1, as a pixel that sometimes finds a small light) goes through the pass loop of
// render/pass_renderer.cpp with the real steps, error estimate and block decision
// (render/noise_estimate.h). The decision TRay used before (the pixel's own error or its 3x3
// neighbourhood's mean, itself included) stops pixels whose samples came out low more often:
// their mean is measurably dark. decideBlock, which reads the neighbours' errors only, gives
// means within Monte Carlo error of the truth, at about the same number of samples.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <vector>

#include "render/noise_estimate.h"

namespace tray {
namespace {

constexpr int kSide = 128;  // 16x16 blocks of 8x8 pixels
constexpr double kBright = 20, kChance = 0.05;

using Decide = std::function<void(std::span<const float>, std::span<const uint32_t>, int, int,
                                  const SamplingPasses&, std::span<uint8_t>)>;

// The rule before the fix: a pixel went on while its own error or its neighbourhood's mean
// error (itself included) was at least its stopping error.
void decideWithOwnError(std::span<const float> error, std::span<const uint32_t> count, int w, int h,
                        const SamplingPasses& passes, std::span<uint8_t> more) {
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int p = y * w + x;
      more[p] = 0;
      if (nextStep(int(count[p]), passes) == 0) continue;
      if (int(count[p]) < passes.minSamples) {
        more[p] = 1;
        continue;
      }
      double sum = 0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          sum += std::isfinite(error[ny * w + nx]) ? error[ny * w + nx] : INFINITY;
          ++n;
        }
      const float limit = stoppingError(int(count[p]), passes);
      more[p] = !(error[p] < limit) || !(sum / n < limit);
    }
}

struct Outcome {
  double mean = 0, samplesPerPixel = 0, standardError = 0;
};

/// The image's mean after adaptive passes under `decide`: each pixel draws from its own
/// random stream, in steps, and each 8x8 block decides from its pixels' errors, as the pass
/// renderer does.
Outcome simulate(const Decide& decide, uint64_t seed) {
  SamplingPasses passes;
  passes.threshold = 0.3f, passes.minSamples = 16, passes.maxSamples = 256;
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
        decide(error, count, kNoiseBlock, kNoiseBlock, passes, more);
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

TEST(AdaptiveBias, OwnErrorDarkensNeighboursOnlyDoNot) {
  double before = 0, after = 0, errorBefore = 0, errorAfter = 0;
  const int runs = 4;
  for (uint64_t seed = 1; seed <= runs; ++seed) {
    const Outcome old = simulate(decideWithOwnError, seed);
    const Outcome now = simulate(decideBlock, seed);
    std::printf("seed %d: own error mean %.4f (%.1f spp), neighbours %.4f (%.1f spp), +-%.4f\n",
                int(seed), old.mean, old.samplesPerPixel, now.mean, now.samplesPerPixel,
                now.standardError);
    before += old.mean / runs, after += now.mean / runs;
    errorBefore += old.standardError * old.standardError / (runs * runs);
    errorAfter += now.standardError * now.standardError / (runs * runs);
    // Both rules spend samples where the noise is: neither is uniform sampling.
    EXPECT_LT(now.samplesPerPixel, 0.6 * 256);
  }
  // The failure: the old rule's mean is dark by many standard errors.
  EXPECT_LT(before, 1.0 - 6 * std::sqrt(errorBefore));
  // The fix: within 4 standard errors of the truth.
  EXPECT_NEAR(after, 1.0, 4 * std::sqrt(errorAfter));
}

}  // namespace
}  // namespace tray

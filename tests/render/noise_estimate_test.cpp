// The pieces of noise-driven adaptive sampling that decide (render/noise_estimate.h).
#include "render/noise_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace tray {
namespace {

PixelSums sums(double r, double g, double b, double weight) {
  PixelSums s;
  s.rgb[0] = r * weight, s.rgb[1] = g * weight, s.rgb[2] = b * weight, s.weight = weight;
  return s;
}

// Dammertz et al. §2.1 as Cycles computes it: L1 difference of the means over sqrt(sum).
TEST(NoiseEstimate, ErrorIsTheHalvesDifferenceOverTheRootOfTheMean) {
  EXPECT_EQ(pixelError(sums(1, 2, 3, 16), sums(1, 2, 3, 8)), 0.0f);
  const float e = pixelError(sums(1, 1, 2, 16), sums(1.5, 0.5, 2, 8));
  EXPECT_NEAR(e, 1.0 / (1e-4 + 2.0), 1e-6);
  // Black pixels stay finite (the epsilon), empty buffers are never converged.
  EXPECT_NEAR(pixelError(sums(0, 0, 0, 4), sums(0.001, 0, 0, 2)), 0.001 / 1e-4, 1e-3);
  EXPECT_TRUE(std::isinf(pixelError(sums(1, 1, 1, 4), PixelSums{})));
  EXPECT_TRUE(std::isinf(pixelError(PixelSums{}, PixelSums{})));
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

// A 4x3 block, threshold 0.1: the pixel at (3, 2) is noisy, so its 3x3 neighbourhood goes
// on; the others stop; a pixel below the minimum goes on whatever its error, one at the
// maximum stops whatever its error; threshold 0 only the maximum stops.
TEST(NoiseEstimate, ABlockDecidesOverEachPixelsNeighbourhood) {
  SamplingPasses p;
  p.threshold = 0.1f, p.minSamples = 16, p.maxSamples = 256;
  const int w = 4, h = 3;
  std::vector<float> error(w * h, 0.01f);
  std::vector<uint32_t> count(w * h, 32);
  std::vector<uint8_t> more(w * h);
  error[2 * w + 3] = 0.5f;
  decideBlock(error, count, w, h, p, more);
  const std::vector<uint8_t> expected = {0, 0, 0, 0,  //
                                         0, 0, 1, 1,  //
                                         0, 0, 1, 1};
  EXPECT_EQ(more, expected);
  count[0] = 8;            // below the minimum
  count[2 * w + 3] = 256;  // at the maximum: it stops, its neighbours do not
  error[0] = 0.0f;
  decideBlock(error, count, w, h, p, more);
  EXPECT_EQ(more[0], 1);
  EXPECT_EQ(more[2 * w + 3], 0);
  EXPECT_EQ(more[2 * w + 2], 1);
  error[5] = std::nanf("");  // no estimate: not converged
  decideBlock(error, count, w, h, p, more);
  EXPECT_EQ(more[5], 1);
  p.threshold = 0;
  decideBlock(error, count, w, h, p, more);
  for (int i = 0; i < w * h; ++i) EXPECT_EQ(more[i], i == 2 * w + 3 ? 0 : 1) << i;
}

}  // namespace
}  // namespace tray

// The two random sequences of core/sampler.h: independent hashing and Owen-scrambled Sobol'.
#include "core/sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "core/error.h"

namespace tray {
namespace {

using Sequence = Sampler::Sequence;

TEST(SobolTest, DimensionsMatchTheSobolSequence) {
  // Sobol' (1967) dimension 1 in natural (not Gray-code) order: the XOR of the direction
  // numbers 1/2, 3/4, 5/8 selected by the index bits; dimension 0 is van der Corput.
  const double dim1[8] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  const double dim0[8] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) {
    EXPECT_EQ(sobol::dimension1(i) / 4294967296.0, dim1[i]) << i;
    EXPECT_EQ(sobol::dimension0(i) / 4294967296.0, dim0[i]) << i;
  }
}

TEST(SobolTest, ThirdDimensionMatchesJoeKuo) {
  // Dimension 3 of Joe & Kuo's table (s = 2, a = 1, m = 1, 3): direction numbers 1/2, 3/4,
  // 3/8 (m_3 = 2 m_2 ^ 4 m_1 ^ m_1 = 3), so points 0, 1/2, 3/4, 1/4, 3/8, 7/8, 1/8, 5/8.
  const double expected[8] = {0, 0.5, 0.75, 0.25, 0.375, 0.875, 0.625, 0.125};
  for (uint32_t i = 0; i < 8; ++i)
    EXPECT_EQ(sobol::dimension2Reference(i) / 4294967296.0, expected[i]) << i;
}

TEST(SobolTest, TablesAndShortcutsMatchTheDefinitions) {
  for (uint32_t i : {0u, 1u, 2u, 255u, 256u, 0x12345678u, 0x80000000u, 0xffffffffu}) {
    EXPECT_EQ(sobol::dimension1(i), sobol::dimension1Reference(i)) << i;
    EXPECT_EQ(sobol::dimension2(i), sobol::dimension2Reference(i)) << i;
    EXPECT_EQ(sobol::scrambledDimension2(i, 77u), sobol::owenScramble(sobol::dimension2(i), 77u));
    EXPECT_EQ(sobol::scrambledDimension0(i, 77u), sobol::owenScramble(sobol::dimension0(i), 77u));
    EXPECT_EQ(sobol::scrambledDimension1(i, 77u), sobol::owenScramble(sobol::dimension1(i), 77u));
    EXPECT_EQ(sobol::reverseBits(sobol::reverseBits(i)), i);
    EXPECT_EQ(sobol::shuffleReversed(sobol::reverseBits(i), 99u), sobol::shuffle(i, 99u));
  }
  EXPECT_EQ(sobol::reverseBits(1u), 0x80000000u);
}

TEST(SobolTest, ShuffleKeepsAlignedBlocks) {
  // Burley 2020 section 4: the first 2^k shuffled indices are one aligned block of 2^k.
  for (uint32_t seed : {1u, 0x9e3779b9u, 12345u})
    for (int k : {2, 5, 8}) {
      std::set<uint32_t> blocks, seen;
      for (uint32_t i = 0; i < (1u << k); ++i) {
        const uint32_t s = sobol::shuffle(i, seed);
        blocks.insert(s >> k);
        seen.insert(s);
      }
      EXPECT_EQ(blocks.size(), 1u) << "seed " << seed << " k " << k;
      EXPECT_EQ(seen.size(), size_t(1) << k);
    }
}

/// The 2^m points of one pixel's 2D pair at dimension `pair` (next2D calls before it).
std::vector<Vec2> pixelPoints(uint32_t pixel, int m, int pair, Sequence sequence) {
  std::vector<Vec2> points;
  for (uint32_t i = 0; i < (1u << m); ++i) {
    Sampler s(pixel, i, 7, sequence);
    for (int d = 0; d < pair; ++d) s.next2D();
    points.push_back(s.next2D());
  }
  return points;
}

/// True when every elementary interval of area 2^-m (all 2^a x 2^(m-a) grids) holds exactly
/// one point: the (0, m, 2)-net property that makes Sobol' pairs stratified.
bool isNet(const std::vector<Vec2>& points, int m) {
  for (int a = 0; a <= m; ++a) {
    std::vector<int> count(size_t(1) << m, 0);
    for (const Vec2& p : points) {
      const int cx = int(p.x * float(1 << a)), cy = int(p.y * float(1 << (m - a)));
      ++count[size_t(cy) * (size_t(1) << a) + size_t(cx)];
    }
    for (int c : count)
      if (c != 1) return false;
  }
  return true;
}

TEST(SamplerTest, SobolPairsAreNetsInEveryPairAndPixel) {
  for (uint32_t pixel : {0u, 1u, 977u})
    for (int pair : {0, 1, 4})
      for (int m : {4, 6}) {
        EXPECT_TRUE(isNet(pixelPoints(pixel, m, pair, Sequence::kSobol), m))
            << "pixel " << pixel << " pair " << pair << " m " << m;
      }
  // Independent samples are not (the failure the stratification fixes).
  EXPECT_FALSE(isNet(pixelPoints(0, 6, 0, Sequence::kIndependent), 6));
}

TEST(SamplerTest, Sobol3DPointsAreStratified) {
  // next3D: (y, z) is dimensions 0 and 1, a (0, m, 2)-net; x (dimension 2) is stratified in 1D.
  const int m = 6, n = 1 << m;
  std::vector<Vec2> yz;
  std::vector<int> strata(n, 0);
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    Sampler s(21, i, 5, Sequence::kSobol);
    s.next2D();
    const Vec3 u = s.next3D();
    yz.push_back({u.y, u.z});
    ++strata[size_t(u.x * n)];
  }
  EXPECT_TRUE(isNet(yz, m));
  for (int c : strata) EXPECT_EQ(c, 1);
  // Independent: the same values as three next1D calls (images rendered before next3D stay).
  Sampler a(4, 2, 9), b(4, 2, 9);
  const Vec3 u = a.next3D();
  EXPECT_EQ(u.x, b.next1D());
  EXPECT_EQ(u.y, b.next1D());
  EXPECT_EQ(u.z, b.next1D());
}

TEST(SamplerTest, Sobol1DIsStratified) {
  const int n = 64;
  std::vector<int> strata(n, 0);
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    Sampler s(5, i, 3, Sequence::kSobol);
    s.next2D();
    const float u = s.next1D();
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    ++strata[size_t(u * n)];
  }
  for (int c : strata) EXPECT_EQ(c, 1);
}

TEST(SamplerTest, SobolIsUniformAcrossPixelsAndDecorrelatedAcrossPairs) {
  // The scrambles differ per pixel: the first sample of many pixels is uniform (chi-square
  // over 16 bins, 99.9% quantile 37.7), and two different pairs do not correlate.
  const int pixels = 16000, bins = 16;
  std::vector<int> hist(bins, 0);
  double sxy = 0, sx = 0, sy = 0, sxx = 0, syy = 0;
  for (uint32_t p = 0; p < uint32_t(pixels); ++p) {
    Sampler s(p, 0, 11, Sequence::kSobol);
    const Vec2 a = s.next2D(), b = s.next2D();
    ++hist[size_t(a.x * bins)];
    sx += a.x, sy += b.x, sxy += a.x * b.x, sxx += a.x * a.x, syy += b.x * b.x;
  }
  double chi2 = 0, expected = double(pixels) / bins;
  for (int h : hist) chi2 += (h - expected) * (h - expected) / expected;
  EXPECT_LT(chi2, 37.7);
  const double n = pixels;
  const double corr = (sxy / n - sx / n * sy / n) /
                      std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
  EXPECT_LT(std::fabs(corr), 0.04);
}

TEST(SamplerTest, SobolIntegratesSmoothFunctionsWithLessError) {
  // f(x, y) = x y over [0,1)^2 (integral 1/4), 64 samples per pixel, error over 400 pixels:
  // stratified points converge faster than N^-1/2.
  auto rmse = [](Sequence sequence) {
    double sum2 = 0;
    for (uint32_t p = 0; p < 400; ++p) {
      double est = 0;
      for (uint32_t i = 0; i < 64; ++i) {
        Sampler s(p, i, 1, sequence);
        const Vec2 u = s.next2D();
        est += double(u.x) * u.y / 64;
      }
      sum2 += (est - 0.25) * (est - 0.25);
    }
    return std::sqrt(sum2 / 400);
  };
  const double independent = rmse(Sequence::kIndependent), stratified = rmse(Sequence::kSobol);
  std::printf("x*y with 64 samples: RMSE independent %.2e, sobol %.2e\n", independent, stratified);
  EXPECT_LT(stratified, 0.1 * independent);
}

TEST(SamplerTest, DeterministicAndNamed) {
  for (Sequence sequence : {Sequence::kIndependent, Sequence::kSobol}) {
    Sampler a(3, 9, 42, sequence), b(3, 9, 42, sequence), c(3, 9, 43, sequence);
    const float va = a.next1D(), vb = b.next1D(), vc = c.next1D();
    EXPECT_EQ(va, vb);
    EXPECT_NE(va, vc);
    EXPECT_EQ(a.dimension(), 1u);
    a.next2D();
    EXPECT_EQ(a.dimension(), 3u);
  }
  EXPECT_EQ(Sampler::parse("sobol"), Sequence::kSobol);
  EXPECT_EQ(Sampler::parse("independent"), Sequence::kIndependent);
  EXPECT_THROW(Sampler::parse("halton"), Error);
}

}  // namespace
}  // namespace tray

// Warping functions of core/sampling.h at the edges of [0,1)^2, where 24-bit uniforms land once
// in 2^24 samples per coordinate.
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace tray {
namespace {

/// Every u with a coordinate at 0 or at the largest float below 1, and a few inside.
std::vector<Vec2> edgeInputs() {
  const float last = 0x1.fffffep-1f;  // 1 - 2^-24
  const std::vector<float> values = {0.0f, 0x1p-24f, 0.194582939f, 0.5f, 0.75f, last};
  std::vector<Vec2> out;
  for (float a : values)
    for (float b : values) out.push_back({a, b});
  return out;
}

TEST(SampleCosineHemisphere, NeverReturnsTheHorizon) {
  // u = (0.194582939, 0) is the furnace's lost sample (issue 18): it mapped to z = 0, pdf 0.
  for (const Vec2& u : edgeInputs()) {
    const Vec3 w = sampleCosineHemisphere(u);
    EXPECT_GT(w.z, 0.0f) << u.x << ", " << u.y;
    EXPECT_GT(cosineHemispherePdf(w.z), 0.0f) << u.x << ", " << u.y;
    EXPECT_NEAR(length(w), 1.0f, 1e-6f) << u.x << ", " << u.y;
  }
}

TEST(SampleCosineHemisphere, InteriorUnchanged) {
  // Away from the rim the direction is Malley's: z = sqrt(1 - x^2 - y^2) exactly.
  for (const Vec2 u : {Vec2{0.3f, 0.6f}, Vec2{0.5f, 0.5f}, Vec2{0.9f, 0.1f}, Vec2{0.01f, 0.4f}}) {
    const Vec3 w = sampleCosineHemisphere(u);
    EXPECT_FLOAT_EQ(w.z, std::sqrt(std::max(0.0f, 1.0f - w.x * w.x - w.y * w.y)));
  }
  EXPECT_EQ(sampleCosineHemisphere(Vec2{0.5f, 0.5f}).z, 1.0f);
}

/// Distance in units in the last place of the float nearest `exact`.
double ulps(float got, double exact) {
  const float nearest = float(exact);
  const double ulp = std::nextafter(std::fabs(nearest), INFINITY) - std::fabs(nearest);
  return std::fabs(double(got) - exact) / ulp;
}

TEST(SinCosQuarterPi, WithinTwoUlpsOverItsRange) {
  // The bound core/sampling.h states (1.7 ulps measured); libm's sinf of the rounded angle is
  // 1.9. A coefficient off in its fourth digit fails this by thousands of ulps.
  double worstSine = 0, worstCosine = 0;
  for (int i = -(1 << 20); i <= (1 << 20); ++i) {
    const float t = float(i) / float(1 << 20);
    float s, c;
    sinCosQuarterPi(t, s, c);
    const double angle = 0.78539816339744830962 * double(t);
    if (i != 0) worstSine = std::max(worstSine, ulps(s, std::sin(angle)));
    worstCosine = std::max(worstCosine, ulps(c, std::cos(angle)));
  }
  EXPECT_LT(worstSine, 2.0);
  EXPECT_LT(worstCosine, 2.0);
  float s, c;
  sinCosQuarterPi(0.0f, s, c);
  EXPECT_EQ(s, 0.0f);
  EXPECT_EQ(c, 1.0f);
}

TEST(CosSinTwoPi, EveryQuarterTurn) {
  // Each quadrant's signs and swaps, checked against double precision, and the points where
  // the quarter turn changes (u = 1/8, 3/8, ...) from both sides.
  for (int i = 0; i <= 1 << 16; ++i) {
    const float u = float(i) / float(1 << 16);
    const Vec2 cs = cosSinTwoPi(u);
    const double angle = 6.28318530717958647692 * double(u);
    EXPECT_NEAR(cs.x, std::cos(angle), 3e-7) << u;
    EXPECT_NEAR(cs.y, std::sin(angle), 3e-7) << u;
  }
  for (float u : {0.125f, 0.375f, 0.625f, 0.875f}) {
    for (float v : {std::nextafter(u, 0.0f), u, std::nextafter(u, 1.0f)}) {
      const Vec2 cs = cosSinTwoPi(v);
      EXPECT_NEAR(cs.x, std::cos(6.28318530717958647692 * v), 3e-7) << v;
      EXPECT_NEAR(cs.y, std::sin(6.28318530717958647692 * v), 3e-7) << v;
    }
  }
}

TEST(Atan2Of, WithinTwoUlpsOnTheUnitRatioAndRightInEveryQuadrant) {
  // The bound core/sampling_lanes.h states for kAtanUnit (1.9 ulps measured).
  double worst = 0;
  for (int i = 1; i <= 1 << 20; ++i) {
    const float t = float(i) / float(1 << 20);
    worst = std::max(worst, ulps(atan2Of(t, 1.0f), std::atan(double(t))));
  }
  EXPECT_LT(worst, 2.0);
  // Octants, signs and the axes against libm in double: angles within 3e-7 radians.
  for (int k = 0; k < 3600; ++k) {
    const double a = -3.14159265358979 + 6.28318530717958 * (k + 0.5) / 3600;
    for (const double r : {1e-20, 0.3, 7.0, 1e20}) {
      const float y = float(r * std::sin(a)), x = float(r * std::cos(a));
      EXPECT_NEAR(atan2Of(y, x), std::atan2(double(y), double(x)), 3e-7) << x << ", " << y;
    }
  }
  EXPECT_EQ(atan2Of(0.0f, 0.0f), 0.0f);
  EXPECT_NEAR(atan2Of(0.0f, -1.0f), kPi, 1e-7);
  EXPECT_NEAR(atan2Of(1.0f, 0.0f), 0.5f * kPi, 1e-7);
  EXPECT_NEAR(atan2Of(-1.0f, 0.0f), -0.5f * kPi, 1e-7);
}

TEST(SampleUniformDiskConcentric, BothWedgesOnTheCircleOfTheirRadius) {
  // The x wedge's angle pi/4 (oy/ox) and the y wedge's pi/2 - pi/4 (ox/oy), against libm in
  // double: the polynomials place every point within a few float ulps of the map's.
  for (int i = 0; i < 256; ++i)
    for (int j = 0; j < 256; ++j) {
      const Vec2 u{(float(i) + 0.5f) / 256.0f, (float(j) + 0.5f) / 256.0f};
      const double ox = 2.0 * u.x - 1.0, oy = 2.0 * u.y - 1.0;
      const bool xWedge = std::fabs(ox) > std::fabs(oy);
      const double r = xWedge ? ox : oy;
      const double theta = xWedge ? 0.78539816339744830962 * (oy / ox)
                                  : 1.57079632679489661923 - 0.78539816339744830962 * (ox / oy);
      const Vec2 d = sampleUniformDiskConcentric(u);
      EXPECT_NEAR(d.x, r * std::cos(theta), 4e-7) << u.x << ", " << u.y;
      EXPECT_NEAR(d.y, r * std::sin(theta), 4e-7) << u.x << ", " << u.y;
    }
  EXPECT_EQ(sampleUniformDiskConcentric(Vec2{0.5f, 0.5f}).x, 0.0f);
}

}  // namespace
}  // namespace tray

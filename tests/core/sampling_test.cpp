// Warping functions of core/sampling.h at the edges of [0,1)^2, where 24-bit uniforms land once
// in 2^24 samples per coordinate.
#include "core/sampling.h"

#include <gtest/gtest.h>

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
  EXPECT_EQ(sampleCosineHemisphere({0.5f, 0.5f}).z, 1.0f);
}

}  // namespace
}  // namespace tray

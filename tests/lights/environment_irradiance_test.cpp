// Irradiance from nine spherical harmonics (lights/environment_irradiance.h) against closed
// forms: a constant environment gives pi L for every normal; two hemispheres give the linear
// pi [(L1 + L2) / 2 + (L1 - L2) / 2 n.y] (bands 0 and 1 exactly); a smooth sky stays within
// Ramamoorthi & Hanrahan's 3% of the irradiance integrated directly.
#include "lights/environment_irradiance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bench/sky_maps.h"
#include "core/sampling.h"
#include "lights/environment_light.h"
#include "lights/image_environment_light.h"

namespace tray {
namespace {

const Vec3 kNormals[] = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0.6f, 0.5f, 0.2f}, {-0.3f, -0.7f, 0.5f}};

TEST(EnvironmentIrradiance, ConstantEnvironmentGivesPiL) {
  const EnvironmentLight light(Color(0.7f, 1.0f, 2.0f), 1);
  const EnvironmentIrradiance e(light);
  for (Vec3 n : kNormals) {
    const Color E = e.irradiance(normalize(n));
    EXPECT_NEAR(E.x, kPi * 0.7f, 1e-3f);
    EXPECT_NEAR(E.z, kPi * 2.0f, 2e-3f);
  }
}

TEST(EnvironmentIrradiance, TwoHemispheresAreLinearInTheNormal) {
  const float L1 = 3.0f, L2 = 0.5f;
  const ImageEnvironmentLight light(maps::hemispheres(256, 128, Color(L1), Color(L2)), 0, 1, 1);
  const EnvironmentIrradiance e(light);
  for (Vec3 n : kNormals) {
    n = normalize(n);
    const float expected = kPi * ((L1 + L2) / 2 + (L1 - L2) / 2 * n.y);
    EXPECT_NEAR(e.irradiance(n).x, expected, 0.01f * expected) << n.x << " " << n.y;
  }
}

TEST(EnvironmentIrradiance, SmoothSkyWithinThreePercentOfTheIntegral) {
  // A sky bright towards +y and +x (no sun: a small bright source needs more bands, which the
  // cosine's smoothing then damps; R&H's bound is for the irradiance's average error).
  auto map = maps::makeMap(128, 64, "sky", [](const Vec3& d) {
    return Color(1.0f + 2.0f * std::max(d.y, 0.0f) + 0.5f * d.x * d.x);
  });
  const ImageEnvironmentLight light(map, 0, 1, 1);
  const EnvironmentIrradiance e(light);
  for (Vec3 n : kNormals) {
    n = normalize(n);
    double sum = 0;  // E(n) = int L max(0, n.w) dw, by a fine midpoint rule
    const int w = 512, h = 256;
    for (int j = 0; j < h; ++j) {
      const double theta = kPi * (j + 0.5) / h;
      for (int i = 0; i < w; ++i) {
        const double phi = 2 * kPi * (i + 0.5) / w;
        const Vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                     float(std::sin(theta) * std::sin(phi)));
        sum += light.Le(d).x * std::max(0.0f, dot(n, d)) * std::sin(theta) * (kPi / h) *
               (2 * kPi / w);
      }
    }
    EXPECT_NEAR(e.irradiance(n).x, sum, 0.03 * sum) << n.x << " " << n.y;
  }
}

}  // namespace
}  // namespace tray

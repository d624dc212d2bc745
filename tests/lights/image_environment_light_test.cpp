// The image environment light against closed forms: its (u, v) convention is Mitsuba 3's, its
// direction pdf integrates to 1 over the sphere, samples follow that pdf (a chi-square test
// whose bins are equal-solid-angle cells, the pole rows included), pdf() answers for MIS what
// sample() returned, Le along a sampled direction is the map at the sampled (u, v), and a
// constant map has the constant environment's power.
#include "lights/image_environment_light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "bench/sky_maps.h"
#include "core/sampler.h"
#include "lights/environment_light.h"

namespace tray {
namespace {

/// A 32 x 16 map with a different luminance in every pixel, bright pixels in the rows at both
/// poles and a dark (zero) patch: every part of the sampling code has something to get wrong.
std::shared_ptr<EnvironmentMap> bumpyMap() {
  auto m = maps::makeMap(32, 16, "bumpy", [](const Vec3& d) {
    const float a = 1.0f + 0.8f * std::sin(7 * d.x + 3 * d.z) * std::cos(5 * d.y);
    return Color(a, 0.5f * a, 2.0f * a);
  });
  auto set = [&](int x, int y, float v) {
    for (int c = 0; c < 3; ++c) m->rgb[(size_t(y) * 32 + size_t(x)) * 3 + size_t(c)] = v;
  };
  set(5, 0, 60), set(20, 15, 40), set(11, 7, 25);
  for (int y = 9; y < 12; ++y)
    for (int x = 24; x < 29; ++x) set(x, y, 0);
  return m;
}

TEST(ImageEnvironmentLight, FollowsMitsubasLatLongConvention) {
  const ImageEnvironmentLight light(bumpyMap(), 0, 1, 1);
  auto near = [](Vec3 a, Vec3 b) { return length(a - b) < 1e-5f; };
  EXPECT_TRUE(near(light.uvToDirection({0.5f, 0.5f}), {0, 0, 1}));    // centre column: +Z
  EXPECT_TRUE(near(light.uvToDirection({0.25f, 0.5f}), {1, 0, 0}));   // +X
  EXPECT_TRUE(near(light.uvToDirection({0.0f, 0.5f}), {0, 0, -1}));   // left edge: -Z
  EXPECT_TRUE(near(light.uvToDirection({0.3f, 0.0f}), {0, 1, 0}));    // top row: +Y
  // Mitsuba's to_world = rotate([0, 1, 0], 90): the centre column turns from +Z to +X.
  const ImageEnvironmentLight turned(bumpyMap(), 90, 1, 1);
  EXPECT_TRUE(near(turned.uvToDirection({0.5f, 0.5f}), {1, 0, 0}));
  const Vec2 uv = turned.directionToUv({1, 0, 0});
  EXPECT_NEAR(uv.x, 0.5f, 1e-6f);
  EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
}

TEST(ImageEnvironmentLight, DirectionPdfIntegratesToOne) {
  const ImageEnvironmentLight light(bumpyMap(), 30, 1, 1);
  // Midpoint rule in (phi, theta) with d omega = sin(theta) d theta d phi: the pdf's
  // 1 / sin(theta) near the poles (the lat-long Jacobian) cancels, so the rule converges.
  const int nPhi = 1024, nTheta = 1024;
  double sum = 0;
  for (int i = 0; i < nTheta; ++i) {
    const double theta = kPi * (i + 0.5) / nTheta;
    for (int j = 0; j < nPhi; ++j) {
      const double phi = 2 * kPi * (j + 0.5) / nPhi;
      const Vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                   float(std::sin(theta) * std::sin(phi)));
      sum += light.pdf({}, d, {}, {}) * std::sin(theta);
    }
  }
  EXPECT_NEAR(sum * (2 * kPi / nPhi) * (kPi / nTheta), 1.0, 1e-3);
}

/// Upper tail of the chi-square distribution (Wilson-Hilferty normal approximation).
double chiSquarePValue(double x, int dof) {
  const double k = dof, t = (std::cbrt(x / k) - (1 - 2 / (9 * k))) / std::sqrt(2 / (9 * k));
  return 0.5 * std::erfc(t / std::sqrt(2.0));
}

TEST(ImageEnvironmentLight, SamplesFollowThePdfChiSquare) {
  // Bins: 24 in phi x 24 in z (equal solid angle, unrelated to the map's pixels, pole caps
  // included); the expected count of each integrates pdf() over it on a 64 x 64 grid (in
  // theta: the pdf's pole singularity cancels against sin(theta)).
  const ImageEnvironmentLight light(bumpyMap(), 17, 1, 1);
  const int nb = 24, sub = 64, samples = 400000;
  std::vector<double> expected(size_t(nb) * nb, 0.0), observed(expected.size(), 0.0);
  auto bin = [&](const Vec3& d) {
    double phi = std::atan2(double(d.z), double(d.x));
    if (phi < 0) phi += 2 * kPi;
    const int bp = std::min(nb - 1, int(phi / (2 * kPi) * nb));
    const int bz = std::clamp(int((d.y + 1) / 2 * nb), 0, nb - 1);
    return size_t(bz) * nb + size_t(bp);
  };
  for (int bz = 0; bz < nb; ++bz) {
    // The bin's theta range, integrated in theta (sin(theta) d theta d phi; see above).
    const double t0 = std::acos(-1 + 2.0 * (bz + 1) / nb), t1 = std::acos(-1 + 2.0 * bz / nb);
    for (int bp = 0; bp < nb; ++bp)
      for (int i = 0; i < sub; ++i)
        for (int j = 0; j < sub; ++j) {
          const double theta = t0 + (t1 - t0) * (i + 0.5) / sub;
          const double phi = 2 * kPi * (bp + (j + 0.5) / sub) / nb;
          const Vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                       float(std::sin(theta) * std::sin(phi)));
          expected[size_t(bz) * nb + size_t(bp)] += light.pdf({}, d, {}, {}) * std::sin(theta) *
                                                    (t1 - t0) / sub * (2 * kPi / nb / sub) *
                                                    samples;
        }
  }
  for (int i = 0; i < samples; ++i) {
    Sampler u(1, uint32_t(i), 9);
    const LightSample s = light.sample({}, u.next2D());
    ASSERT_TRUE(s.valid());
    observed[bin(s.wi)] += 1;
  }
  // Bins expecting fewer than 5 are pooled (the usual rule for the test to hold).
  double chi2 = 0, pooledE = 0, pooledO = 0;
  int dof = -1;
  for (size_t b = 0; b < expected.size(); ++b) {
    if (expected[b] < 5) {
      pooledE += expected[b], pooledO += observed[b];
      continue;
    }
    chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
    ++dof;
  }
  if (pooledE > 0) chi2 += (pooledO - pooledE) * (pooledO - pooledE) / pooledE, ++dof;
  ASSERT_GT(dof, 400);
  EXPECT_GT(chiSquarePValue(chi2, dof), 1e-3) << "chi2 " << chi2 << " dof " << dof;
  // The pole caps (first and last z bins) received what they should.
  double capE = 0, capO = 0;
  for (int bp = 0; bp < nb; ++bp)
    for (size_t row : {size_t(0), size_t(nb - 1)})
      capE += expected[row * nb + size_t(bp)], capO += observed[row * nb + size_t(bp)];
  EXPECT_NEAR(capO, capE, 4 * std::sqrt(capE));
}

TEST(ImageEnvironmentLight, SamplesRoundTripThroughLeAndPdf) {
  const ImageEnvironmentLight light(bumpyMap(), -63, 2.5f, 1);
  for (int i = 0; i < 2000; ++i) {
    Sampler u(2, uint32_t(i), 4);
    const LightSample s = light.sample({}, u.next2D());
    ASSERT_TRUE(s.valid());
    EXPECT_NEAR(length(s.wi), 1.0f, 1e-5f);
    EXPECT_TRUE(s.infinite);
    const Color Le = light.Le(s.wi);
    EXPECT_NEAR(Le.x, s.L.x, 2e-3f * (1 + s.L.x)) << i;
    EXPECT_NEAR(Le.z, s.L.z, 2e-3f * (1 + s.L.z)) << i;
    EXPECT_NEAR(light.pdf({}, s.wi, {}, {}), s.pdf, 2e-3f * s.pdf) << i;
    const Vec2 uv = light.directionToUv(s.wi);
    EXPECT_LT(length(light.uvToDirection(uv) - s.wi), 1e-4f);
  }
  // Where the map is zero (and its neighbours too) nothing is sampled: pdf 0 there.
  const Vec3 dark = light.uvToDirection({(26 + 0.5f) / 32, (10 + 0.5f) / 16});
  EXPECT_EQ(light.pdf({}, dark, {}, {}), 0.0f);
  EXPECT_EQ(light.Le(dark).x, 0.0f);
}

TEST(ImageEnvironmentLight, ConstantMapHasTheConstantEnvironmentsPower) {
  const auto grey = maps::hemispheres(256, 128, Color(0.7f), Color(0.7f));
  const ImageEnvironmentLight image(grey, 0, 2, 3);
  const EnvironmentLight constant(Color(1.4f), 3);
  EXPECT_NEAR(image.power(), constant.power(), 1e-3 * constant.power());
  EXPECT_NEAR(image.Le({0.3f, -0.9f, 0.1f}).y, 1.4f, 1e-5f);
}

}  // namespace
}  // namespace tray

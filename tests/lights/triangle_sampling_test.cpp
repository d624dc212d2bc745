// Emissive triangles sampled by area, by solid angle and by pbrt-v4's choice between them
// (lights/triangle_light_lanes.h, --triangle-sampling): for triangles far, near, grazing, small
// and tiny, in every mode, a chi-square test of AreaLight::sample against AreaLight::pdf (the
// density MIS uses), each sample's pdf equal to AreaLight::pdf's for its direction, and the
// pdf integrating to 1 over the directions that meet the triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "lights/area_light.h"
#include "tests/materials/chi2.h"

namespace tray {
namespace {

struct Case {
  const char* name;
  Vec3 p0, p1, p2, ref;
};

// Receivers at the origin but for the near one; the triangles face both ways (double-sided).
const Case kCases[] = {
    {"far", {-0.5f, 2, -0.3f}, {0.6f, 2, -0.4f}, {0.1f, 2, 0.7f}, {0, 0, 0}},
    {"near-large", {-3, 0, -2}, {3, 0, -2}, {0, 0, 4}, {0.1f, -0.05f, 0.3f}},
    {"grazing", {0.3f, 0.02f, -1}, {2, 0.02f, -1}, {1, 0.02f, 1.5f}, {0, 0, 0}},
    {"small", {-0.05f, 3, 0}, {0.05f, 3, 0}, {0, 3, 0.08f}, {0, 0, 0}},  // ~4e-4 sr
    {"tiny", {-0.01f, 3, 0}, {0.01f, 3, 0}, {0, 3, 0.016f}, {0, 0, 0}},  // ~2e-5 sr
};

/// The triangle as a square: barycentrics (b1, b2) = (S (1 - T), S T), binned in (S^2, T),
/// where each bin has the same area. Directions that meet the triangle and its points are one
/// to one, so a histogram of the sampled points tests the directions' distribution; and unlike
/// a grid of directions around the triangle, no bin straddles its edges: the expected counts
/// integrate a smooth density, accurate for slivers seen at grazing angles too.
constexpr int kSBins = 24, kTBins = 24;

const char* modeName(TriangleSampling m) {
  return m == TriangleSampling::kArea ? "area" : m == TriangleSampling::kAuto ? "auto" : "solid";
}

/// The bin of point p (in double: barycentrics from the Gram matrix of the edges).
int binOf(const Case& c, const Vec3& p) {
  const Vec3 e1 = c.p1 - c.p0, e2 = c.p2 - c.p0, d = p - c.p0;
  const double a11 = dot(e1, e1), a12 = dot(e1, e2), a22 = dot(e2, e2);
  const double r1 = dot(d, e1), r2 = dot(d, e2), det = a11 * a22 - a12 * a12;
  const double b1 = (r1 * a22 - r2 * a12) / det, b2 = (r2 * a11 - r1 * a12) / det;
  const double sum = std::clamp(b1 + b2, 0.0, 1.0), t = sum > 0 ? b2 / sum : 0.0;
  const int i = std::clamp(int(sum * sum * kSBins), 0, kSBins - 1);
  const int j = std::clamp(int(t * kTBins), 0, kTBins - 1);
  return i * kTBins + j;
}

void checkCase(const Case& c, TriangleSampling mode) {
  SCOPED_TRACE(std::string(c.name) + " " + modeName(mode));
  const Vec3 n = normalize(cross(c.p1 - c.p0, c.p2 - c.p0));
  const AreaLight light = AreaLight::triangle(c.p0, c.p1, c.p2, n, Color(1.0f), true, mode);
  // A tilted receiver: the warp by its cosines (cosineWarpOf) varies over the triangle.
  const LightSampleContext ctx{c.ref, normalize(Vec3(0.3f, 1, -0.2f)), true, true};
  // Observed: 300k samples; each one's pdf against AreaLight::pdf at its point.
  std::vector<double> observed(kSBins * kTBins, 0.0), expected(observed.size(), 0.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const int samples = 300000;
  for (int i = 0; i < samples; ++i) {
    const LightSample s = light.sample(ctx, Vec2{u01(rng), u01(rng)});
    ASSERT_TRUE(s.valid());
    observed[size_t(binOf(c, s.p))] += 1;
    const float pdf = light.pdf(ctx, s.wi, s.p, n);
    ASSERT_NEAR(pdf / s.pdf, 1.0f, 2e-4f) << i;
  }
  // Expected: the solid-angle pdf over each bin, pdf(w) |cos| / d^2 dA, 32 x 32 midpoints
  // each (dA = area d(S^2) dT).
  const int sub = 32;
  const double dS2 = 1.0 / (kSBins * sub), dT = 1.0 / (kTBins * sub);
  double integral = 0;
  for (int i = 0; i < kSBins * sub; ++i)
    for (int j = 0; j < kTBins * sub; ++j) {
      const float S = float(std::sqrt((i + 0.5) * dS2)), T = float((j + 0.5) * dT);
      const Vec3 p = c.p0 + (S * (1 - T)) * (c.p1 - c.p0) + (S * T) * (c.p2 - c.p0);
      const Vec3 d = p - c.ref;
      const double dist2 = dot(d, d);
      const Vec3 w = d / std::sqrt(float(dist2));
      const double jacobian = std::fabs(double(dot(n, w))) / dist2 * light.area();
      const double mass = double(light.pdf(ctx, w, p, n)) * jacobian * dS2 * dT;
      expected[size_t((i / sub) * kTBins + j / sub)] += mass * samples;
      integral += mass;
    }
  EXPECT_NEAR(integral, 1.0, 2e-3);
  double chi2 = 0, pooledObs = 0, pooledExp = 0;
  int dof = -1;
  for (size_t b = 0; b < observed.size(); ++b) {
    if (expected[b] < 5) {
      pooledObs += observed[b], pooledExp += expected[b];
      continue;
    }
    chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b], ++dof;
  }
  if (pooledExp >= 5) chi2 += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp, ++dof;
  const double p = test::gammaQ(dof / 2.0, chi2 / 2.0);
  const float omega = sphericalTriangleOf(c.p0 - c.ref, c.p1 - c.ref, c.p2 - c.ref).area;
  std::printf("%-10s %-5s solid angle %.3g sr: chi2 %.1f, dof %d, p %.3f, integral %.5f\n", c.name,
              modeName(mode), double(omega), chi2, dof, p, integral);
  EXPECT_GT(dof, 100);
  EXPECT_GT(p, 1e-3) << "chi2 " << chi2 << " dof " << dof;
}

TEST(TriangleSampling, EveryModeSamplesItsOwnPdfChiSquare) {
  for (const Case& c : kCases)
    for (TriangleSampling m :
         {TriangleSampling::kArea, TriangleSampling::kSolidAngle, TriangleSampling::kAuto})
      checkCase(c, m);
}

TEST(TriangleSampling, SolidAnglePdfIsOneOverTheSolidAngleWhereItIsChosen) {
  // pbrt-v4's rule: by solid angle between 3e-4 and 6.22 sr; forced, down to any positive
  // solid angle; by area elsewhere, with the former pdf. A receiver without a normal: no
  // cosine warp.
  for (const Case& c : kCases) {
    const Vec3 n = normalize(cross(c.p1 - c.p0, c.p2 - c.p0));
    const float omega = sphericalTriangleOf(c.p0 - c.ref, c.p1 - c.ref, c.p2 - c.ref).area;
    const LightSampleContext ctx{c.ref, Vec3(0, 0, 0), true, true};
    const Vec3 p = (c.p0 + c.p1 + c.p2) / 3.0f, d = p - c.ref;
    const float byArea =
        AreaLight::triangle(c.p0, c.p1, c.p2, n, Color(1.0f), true, TriangleSampling::kArea)
            .pdf(ctx, normalize(d), p, n);
    for (TriangleSampling m : {TriangleSampling::kSolidAngle, TriangleSampling::kAuto}) {
      const float pdf = AreaLight::triangle(c.p0, c.p1, c.p2, n, Color(1.0f), true, m)
                            .pdf(ctx, normalize(d), p, n);
      const bool spherical = m == TriangleSampling::kSolidAngle || omega >= 3e-4f;
      EXPECT_FLOAT_EQ(pdf, spherical ? 1.0f / omega : byArea) << c.name << " " << modeName(m);
    }
  }
}


TEST(TriangleSampling, ChoiceBoundIsConservative) {
  // surelyByArea, kAuto's cheap pre-test, must only ever send a triangle to area sampling
  // where the float solid angle is below kMinSphericalSolidAngle (so the choice is the one
  // the exact solid angle makes), and must decide the far, small triangles. Random slivers
  // and fat triangles at 3 to 1000 times their size (solid angles 1e-6 to 0.3 sr).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), scale(-4.0f, 0.0f);
  int decided = 0, below = 0;
  for (int i = 0; i < 200000; ++i) {
    const float size = std::pow(10.0f, scale(rng));
    const Vec3 p0(u(rng), u(rng), u(rng));
    const Vec3 e1 = size * Vec3(u(rng), u(rng), u(rng)),
               e2 = (i % 2 ? 0.01f : 1.0f) * size * Vec3(u(rng), u(rng), u(rng));
    const Vec3 ref = p0 + std::pow(10.0f, 1.75f + 1.25f * u(rng)) * size *
                              normalize(Vec3(u(rng), u(rng), u(rng)));
    const TriangleLightOf<Vec3> t{p0, e1, e2, normalize(cross(e1, e2)), 0.5f, true};
    const float omega = sphericalTriangleFrom(t, ref).area;
    const bool sure = surelyByArea(t, ref);
    below += omega < kMinSphericalSolidAngle;
    decided += sure;
    if (sure) {
      ASSERT_LT(omega, kMinSphericalSolidAngle) << i;
    }
    ASSERT_EQ(bySolidAngle(TriangleSampling::kAuto, omega) && !sure,
              bySolidAngle(TriangleSampling::kAuto, omega)) << i;
  }
  std::printf("surelyByArea decided %d of the %d below the threshold (200000 cases)\n", decided,
              below);
  EXPECT_GT(decided, below / 4);
  // The far and tiny cases of kCases: decided without the solid angle.
  const Case& tiny = kCases[4];
  const TriangleLightOf<Vec3> t{tiny.p0, tiny.p1 - tiny.p0, tiny.p2 - tiny.p0, Vec3(0, 0, 1),
                                1.0f, true};
  EXPECT_TRUE(surelyByArea(t, tiny.ref));
  const Case& far = kCases[0];
  EXPECT_FALSE(surelyByArea(
      TriangleLightOf<Vec3>{far.p0, far.p1 - far.p0, far.p2 - far.p0, Vec3(0, 1, 0), 1.0f, true},
      far.ref));
}

}  // namespace
}  // namespace tray

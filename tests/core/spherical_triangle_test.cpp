// core/spherical_triangle_lanes.h on one float: Van Oosterom & Strackee's solid angle against
// closed forms and Girard's theorem in double, and Arvo's directions inside the spherical
// triangle, spread over it as u says. Its distribution against its pdf (chi-square) is
// tests/lights/triangle_sampling_test.cpp's, through AreaLight.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/spherical_triangle_lanes.h"

namespace tray {
namespace {

struct D3 {
  double x, y, z;
};
D3 d3(const Vec3& v) {
  return {v.x, v.y, v.z};
}
double dotD(const D3& a, const D3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
D3 crossD(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
D3 unitD(const D3& a) {
  const double l = std::sqrt(dotD(a, a));
  return {a.x / l, a.y / l, a.z / l};
}
/// Girard's theorem in double: the sum of the angles minus pi.
double girard(const Vec3& pa, const Vec3& pb, const Vec3& pc) {
  const D3 a = unitD(d3(pa)), b = unitD(d3(pb)), c = unitD(d3(pc));
  const auto angle = [](const D3& at, const D3& p, const D3& q) {
    const D3 n1 = unitD(crossD(at, p)), n2 = unitD(crossD(at, q));
    return std::acos(std::clamp(dotD(n1, n2), -1.0, 1.0));
  };
  return angle(a, b, c) + angle(b, c, a) + angle(c, a, b) - 3.14159265358979323846;
}

TEST(SphericalTriangle, SolidAngleOfAnOctantAndAHalfSpace) {
  EXPECT_NEAR(sphericalTriangleOf(Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)).area, 0.5f * kPi,
              1e-6f);
  // A large triangle just above the point: nearly the half space (the omega > pi side).
  const float h = 1e-2f;
  const float omega =
      sphericalTriangleOf(Vec3(-100, -100, h), Vec3(300, -100, h), Vec3(-100, 300, h)).area;
  EXPECT_NEAR(omega, girard({-100, -100, h}, {300, -100, h}, {-100, 300, h}), 1e-4);
  EXPECT_GT(omega, 6.2f);
}

TEST(SphericalTriangle, SolidAngleMatchesGirardInDoubleAndKeepsSmallOnesRelative) {
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 pa(u(rng), u(rng), 1.5f + u(rng)), pb(u(rng), u(rng), 1.5f + u(rng)),
        pc(u(rng), u(rng), 1.5f + u(rng));
    const double g = girard(pa, pb, pc);
    EXPECT_NEAR(sphericalTriangleOf(pa, pb, pc).area, g, 2e-6 + 2e-6 * g) << i;
  }
  // A 1e-3 triangle at distance 10 (1e-8 sr): Girard's float sum would lose it entirely.
  const Vec3 pa(0, 0, 10), pb(1e-3f, 0, 10), pc(0, 1e-3f, 10);
  const double exact = 0.5e-6 / 100.0;  // area / d^2, to first order
  EXPECT_NEAR(sphericalTriangleOf(pa, pb, pc).area / exact, 1.0, 1e-4);
}

TEST(SphericalTriangle, SamplesLieInsideAndSplitItsAreaAsUSays) {
  // Directions inside: on the inner side of all three great circles. u.x is the fraction of
  // the area in the sub-triangle a b c': the directions with u.x < 1/2 are the half of the
  // triangle on a's side of the arc from b through the sample at u.x = 1/2.
  std::mt19937_64 rng(38);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), u(-1.0f, 1.0f);
  for (int t = 0; t < 200; ++t) {
    const Vec3 pa(u(rng), u(rng), 1 + u(rng)), pb(u(rng), u(rng), 1 + u(rng)),
        pc(u(rng), u(rng), 1 + u(rng));
    const SphericalTriangleOf<Vec3> s = sphericalTriangleOf(pa, pb, pc);
    if (!(s.area > 1e-2f) || !(s.area < 6.0f)) continue;
    const float side = dot(s.a, cross(s.b, s.c)) > 0 ? 1.0f : -1.0f;
    const Vec3 mid = sampleSphericalTriangle(s, Vec2{0.5f, 0.5f});
    const Vec3 split = cross(s.b, mid);  // the great circle b -> (the arc at u.x = 1/2)
    const float aSide = dot(split, s.a);
    for (int i = 0; i < 200; ++i) {
      const Vec2 uu{u01(rng), u01(rng)};
      const Vec3 w = sampleSphericalTriangle(s, uu);
      EXPECT_NEAR(length(w), 1.0f, 1e-5f);
      EXPECT_GE(side * dot(w, cross(s.a, s.b)), -1e-5f) << t << " " << i;
      EXPECT_GE(side * dot(w, cross(s.b, s.c)), -1e-5f) << t << " " << i;
      EXPECT_GE(side * dot(w, cross(s.c, s.a)), -1e-5f) << t << " " << i;
      if (std::fabs(uu.x - 0.5f) > 0.01f && uu.y > 0.01f) {
        EXPECT_EQ(dot(split, w) * aSide > 0, uu.x < 0.5f) << t << " " << i;
      }
    }
  }
}

}  // namespace
}  // namespace tray

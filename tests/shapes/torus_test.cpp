#include "shapes/torus.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "accel/registry.h"
#include "tests/scene_builder.h"
#include "tests/shapes/torus_reference.h"

namespace tray {
namespace {

Ray ray(Vec3 o, Vec3 d) {
  return Ray{o, d, 0.0f, kInfinity};
}

TEST(Torus, ThroughTheEquatorialPlaneCrossesFourTimes) {
  Torus t(2.0f, 0.5f);
  std::vector<Interval> iv;
  t.intervals(ray({-10, 0, 0}, {1, 0, 0}), iv);
  ASSERT_EQ(iv.size(), 2u);
  EXPECT_NEAR(iv[0].enter.t, 7.5f, 1e-5f);
  EXPECT_NEAR(iv[0].exit.t, 8.5f, 1e-5f);
  EXPECT_NEAR(iv[1].enter.t, 11.5f, 1e-5f);
  EXPECT_NEAR(iv[1].exit.t, 12.5f, 1e-5f);
  EXPECT_LT(iv[0].enter.normal.x, 0.0f);  // outward normals
  EXPECT_GT(iv[0].exit.normal.x, 0.0f);
  EXPECT_LT(iv[1].enter.normal.x, 0.0f);
  EXPECT_GT(iv[1].exit.normal.x, 0.0f);
}

TEST(Torus, TheHoleAlongTheAxisIsAMissAndTheTubeAHit) {
  Torus t(2.0f, 0.5f);
  Hit h;
  EXPECT_FALSE(t.intersect(ray({0, 5, 0}, {0, -1, 0}), h));
  ASSERT_TRUE(t.intersect(ray({2, 5, 0}, {0, -1, 0}), h));
  EXPECT_NEAR(h.t, 4.5f, 1e-5f);
  EXPECT_NEAR(normalize(h.normal).y, 1.0f, 1e-6f);
  EXPECT_NEAR(h.uv.y, 0.25f, 1e-6f);  // top of the tube
}

TEST(Torus, FromInsideTheTubeFindsTheExitAndRespectsTheRange) {
  Torus t(2.0f, 0.5f);
  Hit h;
  ASSERT_TRUE(t.intersect(ray({2, 0, 0}, {0, 0, 1}), h));
  // From the tube's centre circle along +z: out where x^2 + z^2 = 2.5^2.
  EXPECT_NEAR(h.t, 1.5f, 1e-5f);
  EXPECT_GT(dot(h.normal, Vec3(2, 0, h.t)), 0.0f);
  Ray shortRay = ray({2, 0, 0}, {0, 0, 1});
  shortRay.tmax = 1.0f;
  EXPECT_FALSE(t.intersect(shortRay, h));
}

TEST(Torus, UnnormalisedAndFarAwayRaysKeepTheirParameter) {
  Torus t(1.0f, 0.01f);
  Hit h;
  ASSERT_TRUE(t.intersect(ray({1, 0, -1e4f}, {0, 0, 4}), h));
  // The line x = 1 touches the centre circle at z = 0: it enters the tube where
  // sqrt(1 + z^2) = 1.01, z = -0.141774.
  EXPECT_NEAR(h.t * 4.0f, 1e4f - 0.141774f, 2e-3f);
  // The normal, computed from the hit point in double: float o + t d at 1e4 is off by ~1e-4,
  // which tilts a 0.01 tube's normal by up to 3e-4 rad. At height y = 0.005 the line x = 1 meets
  // the tube where rho = 1 + sqrt(0.01^2 - 0.005^2); the normal is (p - p_xz / rho) / 0.01.
  const double y = double(0.005f), rho = 1 + std::sqrt(1e-4 - y * y);
  const double z = -std::sqrt(rho * rho - 1), k = 1 - 1 / rho;
  const double nx = k / 0.01, ny = y / 0.01, nz = z * k / 0.01;
  double worst = 1;
  for (int i = 0; i < 50; ++i) {  // origins at different roundings
    ASSERT_TRUE(t.intersect(ray({1, 0.005f, -1e4f - 0.37f * float(i)}, {0, 0, 4}), h));
    const Vec3 n = normalize(h.normal);
    worst = std::min(worst, double(n.x) * nx + double(n.y) * ny + double(n.z) * nz);
  }
  EXPECT_GT(worst, 1.0 - 1e-10);  // float o + t d: 1 - 4.3e-8 (3e-4 rad)
}

TEST(Torus, UvAtKnownPoints) {
  Torus t(2.0f, 0.5f);
  EXPECT_NEAR(t.uvAt({0, 0, 2.5f}).x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.uvAt({0, 0, 2.5f}).y, 0.0f, 1e-6f);  // outer equator
  EXPECT_NEAR(t.uvAt({2.5f, 0, 0}).x, 0.25f, 1e-6f);
  EXPECT_NEAR(t.uvAt({0, 0, 1.5f}).y, 0.5f, 1e-6f);    // inner equator
  EXPECT_NEAR(t.uvAt({0, -0.5f, 2}).y, 0.75f, 1e-6f);  // bottom
}

TEST(Torus, UvDerivativesMatchFiniteDifferences) {
  Torus t(1.5f, 0.4f);
  for (Vec3 q : {Vec3(0.3f, 0.2f, 1.6f), Vec3(-1.2f, -0.3f, 0.4f), Vec3(0.9f, 0.1f, -0.7f)}) {
    Vec3 p = t.refine(q);
    Vec3 dpdu, dpdv;
    t.uvDerivatives(p, t.normalAt(p), dpdu, dpdv);
    const float h = 1e-3f;
    Vec2 uv = t.uvAt(p), uvU = t.uvAt(t.refine(p + h * dpdu)), uvV = t.uvAt(t.refine(p + h * dpdv));
    EXPECT_NEAR((uvU.x - uv.x) / h, 1.0f, 2e-2f);
    EXPECT_NEAR((uvU.y - uv.y) / h, 0.0f, 2e-2f);
    EXPECT_NEAR((uvV.x - uv.x) / h, 0.0f, 2e-2f);
    EXPECT_NEAR((uvV.y - uv.y) / h, 1.0f, 2e-2f);
    EXPECT_NEAR(dot(dpdu, t.normalAt(p)), 0.0f, 1e-4f);
    EXPECT_NEAR(dot(dpdv, t.normalAt(p)), 0.0f, 1e-4f);
  }
}

TEST(Torus, RefineProjectsOntoTheSurface) {
  Torus t(2.0f, 0.5f);
  for (Vec3 q : {Vec3(2.6f, 0.1f, 0.3f), Vec3(-0.3f, 0.45f, -1.9f), Vec3(1.0f, -0.2f, 1.0f)}) {
    Vec3 p = t.refine(q);
    EXPECT_NEAR(double(test::torusDistance(2, 0.5, p.x, p.y, p.z)), 0.0, 1e-6);
  }
}

TEST(Torus, AreaSamplesAreUniformOverTheArea) {
  // Placed by a similarity (scale 2): the area is 4 pi^2 R r s^2. The outer half of the tube
  // (cos v > 0) holds (pi R + 2 r) / (2 pi R) of it, more than half: uniform in v would give
  // exactly half. And every sample lies on the surface with its outward normal.
  const float R = 1.0f, r = 0.6f, s = 2.0f;
  Torus t(R, r);
  const Transform toWorld(Mat4::translate({1, 2, 3}) * Mat4::scale(Vec3(s)));
  EXPECT_NEAR(t.area(toWorld), 4 * kPi * kPi * R * r * s * s, 1e-3f);
  const int n = 200000;
  int outer = 0;
  std::mt19937 g(5);
  for (int i = 0; i < n; ++i) {
    Vec2 u{float(g() >> 8) / 16777216.0f, float(g() >> 8) / 16777216.0f};
    std::optional<ShapeSample> smp = t.sampleArea(toWorld, u);
    ASSERT_TRUE(smp);
    ASSERT_FLOAT_EQ(smp->pdf, 1.0f / t.area(toWorld));
    Vec3 p = toWorld.inversePoint(smp->p);
    ASSERT_NEAR(double(test::torusDistance(R, r, p.x, p.y, p.z)), 0.0, 1e-5);
    ASSERT_GT(dot(smp->n, normalize(toWorld.normal(t.normalAt(p)))), 0.9999f);
    outer += std::sqrt(p.x * p.x + p.z * p.z) > R;
  }
  const double expected = (kPi * R + 2 * r) / (2 * kPi * R);
  EXPECT_NEAR(double(outer) / n, expected, 4 * std::sqrt(expected * (1 - expected) / n));
}

TEST(Torus, SolidAngleSamplingEstimatesTheSubtendedSolidAngle) {
  // Shape::sample's default turns the area samples into solid-angle samples; E[visible / pdf]
  // is the solid angle the torus covers from ref, where only the nearest point of each
  // direction counts (the rest is hidden by the torus itself). Against rays in all directions.
  Torus t(1.0f, 0.4f);
  const Transform toWorld(Mat4::identity());
  const Vec3 ref(0.3f, 1.5f, 2.2f);
  std::mt19937 g(11);
  auto uni = [&] { return float(g() >> 8) / 16777216.0f; };
  const int n = 400000;
  double estimate = 0;
  for (int i = 0; i < n; ++i) {
    std::optional<ShapeSample> s = t.sample({toWorld, ref}, {uni(), uni()});
    if (!s) continue;
    Hit h;
    Ray toward{ref, s->p - ref, 0.0f, 1.0f - 1e-4f};
    if (t.intersect(toward, h)) continue;  // hidden behind the near side
    if (s->pdf < 100) {  // away from grazing, where float rounding of cos dominates
      EXPECT_NEAR(t.pdf({toWorld, ref}, s->p, s->n), s->pdf, 1e-3f * s->pdf);
    }
    estimate += 1.0 / s->pdf;
  }
  estimate /= n;
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    const float z = 2 * uni() - 1, phi = 2 * kPi * uni(), sn = std::sqrt(1 - z * z);
    Hit h;
    hits += t.intersect(ray(ref, {sn * std::cos(phi), z, sn * std::sin(phi)}), h);
  }
  const double direct = 4 * kPi * double(hits) / n;
  EXPECT_NEAR(estimate, direct, 0.02 * direct);
}

TEST(Torus, BothAcceleratorsReportTheSameHits) {
  using namespace tray::test;
  Scene s;
  const int m = addMaterial(s, diffuse(Color(0.5f)));
  addShape(s, std::make_shared<Torus>(1.0f, 0.3f), Mat4::translate({0, 0, 0}), m);
  addShape(s, std::make_shared<Torus>(1.0f, 0.01f),
           Mat4::translate({0.5f, 0.2f, 0}) * Mat4::rotate(0.5f, 0, 0, 0.866f), m);
  addShape(s, std::make_shared<Torus>(0.5f, 0.2f),
           Mat4::translate({0, 1.5f, 0.5f}) * Mat4::scale(Vec3(1.5f)), m);
  s.finalize();
  auto embree = makeAccelerator("embree", s), bvh = makeAccelerator("bvh", s);
  std::mt19937 g(3);
  auto uni = [&] { return float(g() >> 8) / 16777216.0f; };
  int hits = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    Vec3 o{6 * uni() - 3, 6 * uni() - 3, 6 * uni() - 3};
    Vec3 target{2 * uni() - 1, 2.5f * uni() - 0.5f, 2 * uni() - 1};
    Ray r = ray(o, target - o);
    Hit a, b;
    const bool fa = embree->intersect(r, a), fb = bvh->intersect(r, b);
    ASSERT_EQ(fa, fb) << i;
    if (!fa) continue;
    ++hits;
    EXPECT_EQ(a.primitive, b.primitive);
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(embree->occluded(r), bvh->occluded(r));
  }
  EXPECT_GT(hits, n / 4);
}

}  // namespace
}  // namespace tray

// Ray–triangle tests: the watertight test (Woop et al. 2013) against Möller–Trumbore, especially
// on edges shared by two triangles, where only the watertight test can never let a ray through.
#include "accel/bvh_triangle.h"

#include <gtest/gtest.h>

#include <random>

namespace tray {
namespace {

bool watertight(const Vec3& o, const Vec3& d, const Vec3& p0, const Vec3& p1, const Vec3& p2,
                float& t, float& b1, float& b2) {
  return intersectWatertight(prepareWatertight(o, d), p0, p1, p2, 0.0f, kInfinity, t, b1, b2);
}

TEST(BvhTriangle, WatertightGivesEmbreeBarycentricsAndT) {
  const Vec3 p0{0, 0, 0}, p1{2, 0, 0}, p2{0, 2, 0};
  float t, b1, b2;
  ASSERT_TRUE(watertight({0.5f, 0.25f, 3}, {0, 0, -1.5f}, p0, p1, p2, t, b1, b2));
  EXPECT_FLOAT_EQ(t, 2.0f);    // direction not unit: t in units of d
  EXPECT_FLOAT_EQ(b1, 0.25f);  // p = (1 - b1 - b2) p0 + b1 p1 + b2 p2
  EXPECT_FLOAT_EQ(b2, 0.125f);
  // Two-sided, any direction, any dominant axis.
  ASSERT_TRUE(watertight({0.5f, 0.25f, -3}, {0, 0, 1}, p0, p1, p2, t, b1, b2));
  EXPECT_FLOAT_EQ(t, 3.0f);
  ASSERT_TRUE(watertight({-1, -1.75f, 1}, {1.5f, 2, -1}, p0, p1, p2, t, b1, b2));
  EXPECT_FLOAT_EQ(t, 1.0f);
  EXPECT_FALSE(watertight({3, 3, 1}, {0, 0, -1}, p0, p1, p2, t, b1, b2));
  EXPECT_FALSE(watertight({0.5f, 0.25f, 3}, {0, 0, 1}, p0, p1, p2, t, b1, b2));  // behind
}

TEST(BvhTriangle, BothTestsAgreeAwayFromEdges) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int compared = 0;
  for (int i = 0; i < 20000; ++i) {
    Vec3 p0{u(rng), u(rng), u(rng)}, p1{u(rng), u(rng), u(rng)}, p2{u(rng), u(rng), u(rng)};
    Vec3 o{3 * u(rng), 3 * u(rng), 3 * u(rng)}, target{u(rng), u(rng), u(rng)};
    Vec3 d = target - o;
    float t1, u1, v1, t2, u2, v2;
    bool a = watertight(o, d, p0, p1, p2, t1, u1, v1);
    bool b = intersectMollerTrumbore(o, d, p0, p1, p2, 0.0f, kInfinity, t2, u2, v2);
    if (a && b) {
      ++compared;
      EXPECT_NEAR(t1, t2, 1e-4f * std::max(1.0f, t2));
      EXPECT_NEAR(u1, u2, 1e-3f);
      EXPECT_NEAR(v1, v2, 1e-3f);
    } else if (a != b) {
      // Only rays grazing an edge may disagree.
      float margin = std::min({a ? u1 : u2, a ? v1 : v2, 1 - (a ? u1 + v1 : u2 + v2)});
      EXPECT_LT(margin, 1e-4f);
    }
  }
  EXPECT_GT(compared, 1500);
}

/// Rays aimed at points of the diagonal shared by the two triangles of a random quad: the
/// watertight test hits at least one triangle of every pair; Möller–Trumbore lets some through.
TEST(BvhTriangle, SharedEdgesNeverLeakWithWatertightButDoWithMollerTrumbore) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int leaksWatertight = 0, leaksMoller = 0, rays = 0;
  for (int q = 0; q < 2000; ++q) {
    // A planar-ish quad a, b, c, d split along a-c; far from the origin to stress rounding.
    Vec3 base{100 * u(rng), 100 * u(rng), 100 * u(rng)};
    Vec3 a = base, b = base + Vec3(1 + u(rng), 0.1f * u(rng), 0.3f * u(rng));
    Vec3 c = base + Vec3(1 + u(rng), 1 + u(rng), 0.2f * u(rng)),
         d = base + Vec3(0.1f * u(rng), 1 + u(rng), 0.3f * u(rng));
    for (int i = 0; i < 50; ++i, ++rays) {
      float s = 0.05f + 0.9f * u(rng);
      Vec3 onEdge = a + s * (c - a);
      Vec3 o = onEdge + Vec3(20 * u(rng) - 10, 20 * u(rng) - 10, 5 + 10 * u(rng));
      Vec3 dir = onEdge - o;
      float t, b1, b2;
      bool w1 = intersectWatertight(prepareWatertight(o, dir), a, b, c, 0, kInfinity, t, b1, b2);
      bool w2 = intersectWatertight(prepareWatertight(o, dir), a, c, d, 0, kInfinity, t, b1, b2);
      bool m1 = intersectMollerTrumbore(o, dir, a, b, c, 0, kInfinity, t, b1, b2);
      bool m2 = intersectMollerTrumbore(o, dir, a, c, d, 0, kInfinity, t, b1, b2);
      leaksWatertight += !w1 && !w2;
      leaksMoller += !m1 && !m2;
    }
  }
  std::printf("rays through shared edges: %d; leaked: watertight %d, Moller-Trumbore %d\n", rays,
              leaksWatertight, leaksMoller);
  EXPECT_EQ(leaksWatertight, 0);
  EXPECT_GT(leaksMoller, 0);
}

TEST(BvhTriangle, AxisAlignedRayExactlyThroughSharedEdgeHitsOneOrBoth) {
  // Edge (0,0,0)-(1,1,0) shared by two triangles; points (x, x) are exactly on it.
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{1, 1, 0}, d{0, 1, 0};
  for (float x : {0.125f, 0.25f, 0.5f, 0.75f, 0.3f, 0.7f}) {
    for (Vec3 dir : {Vec3(0, 0, -1), Vec3(0, 0, 1)}) {
      Vec3 o{x, x, -dir.z};
      float t, b1, b2;
      bool h1 = intersectWatertight(prepareWatertight(o, dir), a, b, c, 0, kInfinity, t, b1, b2);
      bool h2 = intersectWatertight(prepareWatertight(o, dir), a, c, d, 0, kInfinity, t, b1, b2);
      EXPECT_TRUE(h1 || h2) << x;
    }
  }
}

}  // namespace
}  // namespace tray

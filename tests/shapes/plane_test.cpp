#include "shapes/plane.h"

#include <gtest/gtest.h>

namespace tray {
namespace {

Ray ray(Vec3 o, Vec3 d) {
  return Ray{o, d, 0.0f, kInfinity};
}

TEST(Plane, HitFromAboveAndBelow) {
  Plane p;
  Hit h;
  ASSERT_TRUE(p.intersect(ray({1, 2, 3}, {0, -1, 0}), h));
  EXPECT_FLOAT_EQ(h.t, 2.0f);
  EXPECT_EQ(h.normal, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(h.uv.x, 1.0f);
  EXPECT_FLOAT_EQ(h.uv.y, 3.0f);
  ASSERT_TRUE(p.intersect(ray({0, -1, 0}, {0, 1, 0}), h));
  EXPECT_FLOAT_EQ(h.t, 1.0f);
}

TEST(Plane, UvTilesWithPeriodOne) {
  // uv = (x, z): a texture with REPEAT wrapping tiles once per unit square, both ways.
  Plane p;
  Hit h;
  ASSERT_TRUE(p.intersect(ray({-2.25f, 1, 7.5f}, {0, -1, 0}), h));
  EXPECT_FLOAT_EQ(h.uv.x, -2.25f);
  EXPECT_FLOAT_EQ(h.uv.y, 7.5f);
  Vec3 dpdu, dpdv;
  p.uvDerivatives({0, 0, 0}, {0, 1, 0}, dpdu, dpdv);
  EXPECT_EQ(dpdu, Vec3(1, 0, 0));
  EXPECT_EQ(dpdv, Vec3(0, 0, 1));
}

TEST(Plane, ParallelRayMisses) {
  Plane p;
  Hit h;
  EXPECT_FALSE(p.intersect(ray({0, 1, 0}, {1, 0, 0}), h));
  EXPECT_FALSE(p.intersect(ray({0, 0, 0}, {1, 0, 0}), h));  // lying in the plane: NaN t
}

TEST(Plane, BehindMisses) {
  Plane p;
  Hit h;
  EXPECT_FALSE(p.intersect(ray({0, 1, 0}, {0, 1, 0}), h));
}

TEST(Plane, HalfSpaceIntervals) {
  Plane p;
  std::vector<Interval> iv;
  p.intervals(ray({0, 1, 0}, {0, -1, 0}), iv);  // enters at t = 1, never leaves
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_FLOAT_EQ(iv[0].enter.t, 1.0f);
  EXPECT_EQ(iv[0].exit.t, kInfinity);
  iv.clear();
  p.intervals(ray({0, -1, 0}, {1, 0, 0}), iv);  // parallel, inside
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_EQ(iv[0].enter.t, -kInfinity);
  iv.clear();
  p.intervals(ray({0, 1, 0}, {1, 0, 0}), iv);  // parallel, outside
  EXPECT_TRUE(iv.empty());
}

}  // namespace
}  // namespace tray

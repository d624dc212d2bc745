#include "shapes/box.h"

#include <gtest/gtest.h>

namespace tray {
namespace {

Ray ray(Vec3 o, Vec3 d) { return Ray{o, d, 0.0f, kInfinity}; }

TEST(Box, HitFromOutsideWithFaceNormal) {
  Box b;
  Hit h;
  ASSERT_TRUE(b.intersect(ray({0, 0, -5}, {0, 0, 1}), h));
  EXPECT_FLOAT_EQ(h.t, 4.0f);
  EXPECT_EQ(h.normal, Vec3(0, 0, -1));
  ASSERT_TRUE(b.intersect(ray({5, 0.5f, 0.2f}, {-1, 0, 0}), h));
  EXPECT_EQ(h.normal, Vec3(1, 0, 0));
}

TEST(Box, FromInsideFindsTheExit) {
  Box b;
  Hit h;
  ASSERT_TRUE(b.intersect(ray({0, 0, 0}, {0, 1, 0}), h));
  EXPECT_FLOAT_EQ(h.t, 1.0f);
  EXPECT_EQ(h.normal, Vec3(0, 1, 0));
}

TEST(Box, BehindAndBesideMiss) {
  Box b;
  Hit h;
  EXPECT_FALSE(b.intersect(ray({0, 0, 5}, {0, 0, 1}), h));
  EXPECT_FALSE(b.intersect(ray({2, 0, -5}, {0, 0, 1}), h));
}

TEST(Box, RayInTheFacePlaneDoesNotProduceNaN) {
  // Origin exactly on the x = 1 slab boundary with d.x = 0: 0 * inf would be NaN.
  Box b;
  Hit h;
  ASSERT_TRUE(b.intersect(ray({1, 0, -5}, {0, 0, 1}), h));
  EXPECT_FLOAT_EQ(h.t, 4.0f);
  EXPECT_TRUE(std::isfinite(h.normal.x));
}

TEST(Box, GrazingEdgeHit) {
  Box b;
  Hit h;
  ASSERT_TRUE(b.intersect(ray({-5, 1, 1}, {1, 0, 0}), h));  // along an edge
  EXPECT_FLOAT_EQ(h.t, 4.0f);
}

TEST(Box, FaceUvSpansUnitSquare) {
  Box b({0, 0, 0}, {2, 4, 8});
  Hit h;
  ASSERT_TRUE(b.intersect(ray({1, 3, -1}, {0, 0, 1}), h));  // z face: u from x, v from y
  EXPECT_FLOAT_EQ(h.uv.x, 0.5f);
  EXPECT_FLOAT_EQ(h.uv.y, 0.75f);
}

TEST(Box, IntervalAndRefine) {
  Box b;
  std::vector<Interval> iv;
  b.intervals(ray({0, 0, -3}, {0, 0, 1}), iv);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_FLOAT_EQ(iv[0].enter.t, 2.0f);
  EXPECT_FLOAT_EQ(iv[0].exit.t, 4.0f);
  EXPECT_EQ(b.refine({0.2f, 0.999f, 0.1f}), Vec3(0.2f, 1.0f, 0.1f));
}

}  // namespace
}  // namespace tray

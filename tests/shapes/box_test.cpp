#include "shapes/box.h"

#include <gtest/gtest.h>

#include <optional>

namespace tray {
namespace {

Ray ray(Vec3 o, Vec3 d) {
  return Ray{o, d, 0.0f, kInfinity};
}

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
  // The -Z face seen from -Z: right is -X, up is +Y, v = 0 at the top edge.
  ASSERT_TRUE(b.intersect(ray({1.5f, 3, -1}, {0, 0, 1}), h));
  EXPECT_FLOAT_EQ(h.uv.x, 0.25f);
  EXPECT_FLOAT_EQ(h.uv.y, 0.25f);
}

/// Each face's uv at the corner the viewer outside sees at its top left is (0, 0), at its top
/// right (1, 0), at its bottom left (0, 1): images appear upright and unmirrored.
TEST(Box, EveryFaceIsUprightSeenFromOutside) {
  Box b;  // [-1, 1]^3
  struct Face {
    Vec3 n, right, up;
  };
  const Face faces[] = {
      {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
  };
  for (const Face& f : faces) {
    auto uvAt = [&](float r, float u) {  // point at (r right, u up) on the face, from outside
      Vec3 p = f.n + r * f.right + u * f.up;
      Hit h;
      EXPECT_TRUE(b.intersect(ray(p + 3.0f * f.n, -f.n), h));
      return h.uv;
    };
    Vec2 topLeft = uvAt(-0.5f, 0.5f), topRight = uvAt(0.5f, 0.5f), bottomLeft = uvAt(-0.5f, -0.5f);
    EXPECT_NEAR(topLeft.x, 0.25f, 1e-6f) << f.n.x << f.n.y << f.n.z;
    EXPECT_NEAR(topLeft.y, 0.25f, 1e-6f) << f.n.x << f.n.y << f.n.z;
    EXPECT_NEAR(topRight.x, 0.75f, 1e-6f) << f.n.x << f.n.y << f.n.z;
    EXPECT_NEAR(bottomLeft.y, 0.75f, 1e-6f) << f.n.x << f.n.y << f.n.z;
    // dp/du points right and dp/dv down, each spanning the face's edge length 2.
    Vec3 dpdu, dpdv;
    b.uvDerivatives(f.n, f.n, dpdu, dpdv);
    EXPECT_EQ(dpdu, 2.0f * f.right);
    EXPECT_EQ(dpdv, -2.0f * f.up);
  }
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

TEST(Box, AreaSamplesAreUniformOverTheWorldSurfaceUnderANonUniformScale) {
  // [-1, 1]^3 scaled by (2, 1, 0.5): a 4 x 2 x 1 box of area 2 (8 + 4 + 2) = 28. Faces are
  // picked by world area; every sample lies on a face with its outward normal, pdf 1 / 28.
  Box b;
  const Transform t(Mat4::translate({1, 2, 3}) * Mat4::scale({2, 1, 0.5f}));
  EXPECT_NEAR(b.area(t), 28.0f, 1e-4f);
  EXPECT_EQ(b.area(Transform()), 24.0f);
  int perAxis[3] = {0, 0, 0};
  const int n = 28000;
  for (int i = 0; i < n; ++i) {
    const Vec2 u{(float(i) + 0.5f) / n, float((i * 7919) % n) / n};
    std::optional<ShapeSample> s = b.sampleArea(t, u);
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->pdf, 1.0f / 28.0f, 1e-6f);
    const Vec3 q = t.inversePoint(s->p), aq = abs(q);
    const int axis = aq.x >= aq.y && aq.x >= aq.z ? 0 : (aq.y >= aq.z ? 1 : 2);
    EXPECT_NEAR(aq[axis], 1.0f, 1e-5f);
    EXPECT_NEAR(s->n[axis], q[axis] > 0 ? 1.0f : -1.0f, 1e-6f);
    ++perAxis[axis];
  }
  // x faces 2 x 1 each, y faces 4 x 1, z faces 4 x 2: shares 4/28, 8/28, 16/28.
  EXPECT_NEAR(perAxis[0], n * 4 / 28, 2);
  EXPECT_NEAR(perAxis[1], n * 8 / 28, 2);
  EXPECT_NEAR(perAxis[2], n * 16 / 28, 2);
}

}  // namespace
}  // namespace tray

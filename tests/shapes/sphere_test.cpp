#include "shapes/sphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace tray {
namespace {

Ray ray(Vec3 o, Vec3 d) {
  return Ray{o, d, 0.0f, kInfinity};
}

TEST(Sphere, HitFromOutside) {
  Sphere s(2.0f);
  Hit h;
  ASSERT_TRUE(s.intersect(ray({0, 0, -10}, {0, 0, 1}), h));
  EXPECT_FLOAT_EQ(h.t, 8.0f);
  EXPECT_FLOAT_EQ(normalize(h.normal).z, -1.0f);
}

TEST(Sphere, FromInsideFindsTheExit) {
  Sphere s(1.0f);
  Hit h;
  ASSERT_TRUE(s.intersect(ray({0, 0, 0.5f}, {0, 0, 1}), h));
  EXPECT_FLOAT_EQ(h.t, 0.5f);
  EXPECT_GT(h.normal.z, 0.0f);  // outward normal at the exit
}

TEST(Sphere, BehindTheRayIsAMiss) {
  Sphere s(1.0f);
  Hit h;
  EXPECT_FALSE(s.intersect(ray({0, 0, 5}, {0, 0, 1}), h));
}

TEST(Sphere, TangentRayTouchesOnce) {
  Sphere s(1.0f);
  Hit h;
  ASSERT_TRUE(s.intersect(ray({1, 0, -5}, {0, 0, 1}), h));
  EXPECT_NEAR(h.t, 5.0f, 1e-3f);
  EXPECT_FALSE(s.intersect(ray({1.0001f, 0, -5}, {0, 0, 1}), h));
}

TEST(Sphere, DistantSmallSphereStaysPrecise) {
  // The textbook b^2 - 4ac loses every digit here; Ray Tracing Gems ch. 7's form does not.
  Sphere s(0.01f);
  Hit h;
  ASSERT_TRUE(s.intersect(ray({0, 0, -1e5f}, {0, 0, 1}), h));
  EXPECT_NEAR(h.t, 1e5f - 0.01f, 0.02f);
  ASSERT_TRUE(s.intersect(ray({0.0099f, 0, -1e5f}, {0, 0, 1}), h));
}

TEST(Sphere, UnnormalisedDirectionKeepsParameter) {
  Sphere s(1.0f);
  Hit h;
  ASSERT_TRUE(s.intersect(ray({0, 0, -3}, {0, 0, 2}), h));
  EXPECT_FLOAT_EQ(h.t, 1.0f);
}

TEST(Sphere, IntervalSpansBothRoots) {
  Sphere s(1.0f);
  std::vector<Interval> iv;
  s.intervals(ray({0, 0, -3}, {0, 0, 1}), iv);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_FLOAT_EQ(iv[0].enter.t, 2.0f);
  EXPECT_FLOAT_EQ(iv[0].exit.t, 4.0f);
  EXPECT_LT(iv[0].enter.normal.z, 0.0f);
  EXPECT_GT(iv[0].exit.normal.z, 0.0f);
}

TEST(Sphere, UvAtKnownPoints) {
  Sphere s(1.0f);
  Vec2 top = s.uvAt({0, 1, 0}), front = s.uvAt({0, 0, 1}), side = s.uvAt({1, 0, 0});
  EXPECT_NEAR(top.y, 0.0f, 1e-6f);
  EXPECT_NEAR(front.x, 0.0f, 1e-6f);
  EXPECT_NEAR(front.y, 0.5f, 1e-6f);
  EXPECT_NEAR(side.x, 0.25f, 1e-6f);
}

TEST(Sphere, UvAtMoreKnownPointsAndThroughIntersect) {
  Sphere s(2.0f);
  Vec2 back = s.uvAt({0, 0, -2}), left = s.uvAt({-2, 0, 0}), bottom = s.uvAt({0, -2, 0});
  EXPECT_NEAR(back.x, 0.5f, 1e-6f);
  EXPECT_NEAR(left.x, 0.75f, 1e-6f);
  EXPECT_NEAR(bottom.y, 1.0f, 1e-6f);
  // 45 degrees above the equator on the +X meridian: v = 1/4.
  Vec2 up45 = s.uvAt({std::sqrt(2.0f), std::sqrt(2.0f), 0});
  EXPECT_NEAR(up45.x, 0.25f, 1e-6f);
  EXPECT_NEAR(up45.y, 0.25f, 1e-6f);
  Hit h;
  ASSERT_TRUE(s.intersect(Ray{{5, 0, 0}, {-1, 0, 0}, 0, kInfinity}, h));
  EXPECT_NEAR(h.uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(h.uv.y, 0.5f, 1e-6f);
}

TEST(Sphere, UvDerivativesMatchFiniteDifferences) {
  Sphere s(1.5f);
  for (Vec3 dir : {Vec3(0.3f, 0.5f, 0.8f), Vec3(-0.7f, -0.2f, 0.4f), Vec3(0.1f, 0.9f, -0.5f)}) {
    Vec3 p = s.refine(dir);
    Vec3 dpdu, dpdv;
    s.uvDerivatives(p, p, dpdu, dpdv);
    const float h = 1e-3f;
    Vec2 uv = s.uvAt(p), uvU = s.uvAt(s.refine(p + h * dpdu)), uvV = s.uvAt(s.refine(p + h * dpdv));
    EXPECT_NEAR((uvU.x - uv.x) / h, 1.0f, 2e-2f);
    EXPECT_NEAR((uvU.y - uv.y) / h, 0.0f, 2e-2f);
    EXPECT_NEAR((uvV.x - uv.x) / h, 0.0f, 2e-2f);
    EXPECT_NEAR((uvV.y - uv.y) / h, 1.0f, 2e-2f);
  }
}

TEST(Sphere, RefineProjectsOntoSurface) {
  Sphere s(3.0f);
  Vec3 p = s.refine({0, 3.001f, 0});
  EXPECT_FLOAT_EQ(p.y, 3.0f);
}

TEST(Sphere, ConeSamplesHitTheSphereWithThePdfThatPdfReturns) {
  // pbrt-v4 6.2.4: from outside, directions uniform in the subtended cone; each sample is the
  // nearest point of the sphere along its direction, facing the reference point.
  Sphere sphere(0.5f);
  const Transform t(Mat4::translate({0, 3, 0}) * Mat4::scale(Vec3(2.0f)));  // world radius 1
  EXPECT_NEAR(sphere.area(t), 4.0f * kPi, 1e-5f);
  const Vec3 ref(0.5f, 0, 0.2f), center(0, 3, 0);
  const float d2 = lengthSquared(center - ref), cone = 2 * kPi * (1 - std::sqrt(1 - 1 / d2));
  const ShapeSampleContext ctx{t, ref};
  for (int i = 0; i < 100; ++i) {
    const Vec2 u{(float(i) + 0.5f) / 100, float((i * 37) % 100) / 100};
    std::optional<ShapeSample> s = sphere.sample(ctx, u);
    ASSERT_TRUE(s);
    EXPECT_NEAR(length(s->p - center), 1.0f, 1e-5f);
    EXPECT_NEAR(length(s->p - ref - dot(s->p - ref, s->wi) * s->wi), 0.0f, 1e-5f);
    EXPECT_LE(dot(s->n, s->wi), 1e-5f);  // the near side
    EXPECT_NEAR(s->pdf, 1 / cone, 1e-3f / cone);
    EXPECT_EQ(sphere.pdf(ctx, s->p, s->n), s->pdf);
  }
  EXPECT_FALSE(sphere.sample({t, center}, {0.5f, 0.5f}));  // no samples from inside
}

}  // namespace
}  // namespace tray

#include "core/transform.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace tray {
namespace {

TEST(Transform, InverseRoundTrips) {
  Mat4 m = Mat4::translate({1, 2, 3}) * Mat4::rotate(0.2f, 0.3f, 0.1f, 0.927f) * Mat4::scale({2, 3, 4});
  Transform t(m);
  Vec3 p{0.3f, -1.5f, 7.0f};
  Vec3 q = t.inversePoint(t.point(p));
  EXPECT_NEAR(q.x, p.x, 1e-5f);
  EXPECT_NEAR(q.y, p.y, 1e-5f);
  EXPECT_NEAR(q.z, p.z, 1e-5f);
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
  // A 45-degree surface squashed in y: transforming its normal as a vector would tilt it off
  // the surface; the inverse transpose keeps it perpendicular.
  Transform t(Mat4::scale({1, 0.25f, 1}));
  Vec3 tangent{1, -1, 0}, normal{1, 1, 0};
  Vec3 tw = t.vector(tangent), nw = t.normal(normal);
  EXPECT_NEAR(dot(tw, nw), 0.0f, 1e-6f);
  Vec3 wrong = t.vector(normal);
  EXPECT_GT(std::fabs(dot(tw, wrong)), 0.5f);
}

TEST(Transform, QuaternionRotatesAboutAxis) {
  float s = std::sin(kPi / 4), c = std::cos(kPi / 4);  // 90 degrees about +Y
  Transform t(Mat4::rotate(0, s, 0, c));
  Vec3 x = t.vector({1, 0, 0});
  EXPECT_NEAR(x.x, 0.0f, 1e-6f);
  EXPECT_NEAR(x.z, -1.0f, 1e-6f);
}

TEST(Transform, ColumnMajorMatchesGltf) {
  double v[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};  // translation (5, 6, 7)
  Transform t(Mat4::fromColumnMajor(v));
  Vec3 p = t.point({0, 0, 0});
  EXPECT_EQ(p, Vec3(5, 6, 7));
}

TEST(Transform, RejectsSingularAndNaN) {
  EXPECT_THROW(Transform(Mat4::scale({1, 0, 1})), Error);
  Mat4 m;
  m.m[0][3] = std::nanf("");
  EXPECT_THROW(Transform{m}, Error);
}

TEST(Transform, HandednessFromDeterminant) {
  EXPECT_FALSE(Transform(Mat4::scale({1, 2, 3})).swapsHandedness());
  EXPECT_TRUE(Transform(Mat4::scale({-1, 2, 3})).swapsHandedness());
}

}  // namespace
}  // namespace tray

#include "accel/registry.h"
#include "shapes/csg.h"

#include <gtest/gtest.h>

#include <random>

#include "core/accelerator.h"
#include "core/error.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

CsgChild child(std::shared_ptr<const Shape> s, const Mat4& m = Mat4::identity(), int material = -1,
               std::string name = "child") {
  return {std::move(s), Transform(m), material, std::move(name)};
}

std::shared_ptr<Csg> csg(CsgOp op, std::vector<CsgChild> children, std::string name = "csg") {
  return std::make_shared<Csg>(op, std::move(children), std::move(name));
}

Ray ray(Vec3 o, Vec3 d, float tmin = 0.0f) {
  return Ray{o, d, tmin, kInfinity};
}

/// Deterministic rays from a shell of radius `from` towards points in the ball of radius `to`.
std::vector<Ray> rayFan(int n, float from, float to, uint32_t seed = 7) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Ray> rays;
  while (int(rays.size()) < n) {
    Vec3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)};
    if (length(a) < 0.1f || length(a) > 1.0f) continue;
    Vec3 o = normalize(a) * from, target = b * to;
    rays.push_back(ray(o, target - o));
  }
  return rays;
}

// --- Transforms ----------------------------------------------------------------------------

TEST(Csg, TransformsOnNodeAndChildComposeLikeAPlacedShape) {
  // A one-child union is the child itself: a CSG node placed by N holding a sphere placed by C
  // must hit exactly like a sphere placed by N * C, normals included (non-uniform scales).
  Mat4 n = Mat4::translate({0.3f, -0.2f, 0.5f}) * Mat4::rotate(0.2f, 0.3f, 0.1f, 0.927f) *
           Mat4::scale({1.0f, 1.5f, 0.8f});
  Mat4 c = Mat4::rotate(0.0f, 0.0f, 0.3827f, 0.9239f) * Mat4::scale({1.2f, 0.6f, 0.9f});
  Scene s;
  int mat = addMaterial(s, diffuse(Color(0.5f)));
  addShape(s, csg(CsgOp::kUnion, {child(std::make_shared<Sphere>(1.0f), c)}), n, mat);
  addShape(s, std::make_shared<Sphere>(1.0f), n * c, mat);
  s.finalize();
  int hits = 0;
  for (const Ray& r : rayFan(400, 5.0f, 1.5f)) {
    Hit a, b;
    bool ha = s.intersectShape(0, r, a), hb = s.intersectShape(1, r, b);
    ASSERT_EQ(ha, hb);
    if (!ha) continue;
    ++hits;
    EXPECT_NEAR(a.t, b.t, 1e-4f * b.t);
    SurfacePoint sa = s.surface(r, a), sb = s.surface(r, b);
    EXPECT_GT(dot(sa.ng, sb.ng), 1.0f - 1e-5f);
  }
  EXPECT_GT(hits, 100);
}

// --- Sphere minus box against an analytic hemisphere ---------------------------------------

/// The solid {|p| <= 1, x <= 0} traced in double: first boundary after t = 0.
struct HemisphereHit {
  bool hit = false, flat = false, ambiguous = false;
  double t = 0;
};
HemisphereHit traceHemisphere(const Ray& r) {
  double o[3] = {r.o.x, r.o.y, r.o.z}, d[3] = {r.d.x, r.d.y, r.d.z};
  double a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2],
         c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 1.0, disc = b * b - a * c;
  HemisphereHit h;
  if (disc <= 0) return h;
  double t0 = (-b - std::sqrt(disc)) / a, t1 = (-b + std::sqrt(disc)) / a;
  double lo = t0, hi = t1, tPlane = -o[0] / d[0];
  bool loFlat = false, hiFlat = false;
  if (d[0] > 0 && tPlane < hi) hi = tPlane, hiFlat = true;
  if (d[0] < 0 && tPlane > lo) lo = tPlane, loFlat = true;
  if (d[0] == 0 && o[0] > 0) return h;
  if (lo >= hi) return h;
  h.ambiguous = std::fabs(tPlane - t0) < 1e-3 || std::fabs(tPlane - t1) < 1e-3 || disc < 1e-4;
  if (lo > 0)
    h.t = lo, h.flat = loFlat, h.hit = true;
  else if (hi > 0)
    h.t = hi, h.flat = hiFlat, h.hit = true;
  return h;
}

TEST(Csg, SphereMinusBoxIsAHemisphereWithTheBoxMaterialOnTheCut) {
  Scene s;
  int red = addMaterial(s, diffuse(Color(1, 0, 0))),
      green = addMaterial(s, diffuse(Color(0, 1, 0)));
  // The box child is placed by a transform: [-1,1]^3 moved to x in [0, 2], y, z in [-2, 2].
  auto shape = csg(
      CsgOp::kDifference,
      {child(std::make_shared<Sphere>(1.0f), Mat4::identity(), red),
       child(std::make_shared<Box>(), Mat4::translate({1, 0, 0}) * Mat4::scale({1, 2, 2}), green)});
  addShape(s, shape, Mat4::identity(), red);
  s.finalize();
  auto accel = makeAccelerator("embree", s);
  std::vector<Ray> rays = rayFan(600, 3.0f, 1.2f);
  for (const Ray& r : rayFan(200, 0.0f, 0.9f, 11)) rays.push_back(r);  // from inside: centre
  int checked = 0, flat = 0, inside = 0;
  for (const Ray& r : rays) {
    HemisphereHit ref = traceHemisphere(r);
    if (ref.ambiguous) continue;
    Hit h;
    ASSERT_EQ(accel->intersect(r, h), ref.hit) << r.o.x << " " << r.d.x;
    ++checked;
    if (!ref.hit) continue;
    EXPECT_NEAR(h.t, ref.t, 1e-5 * (1 + ref.t));
    SurfacePoint sp = s.surface(r, h);
    Vec3 expectedNormal = ref.flat ? Vec3(1, 0, 0) : normalize(sp.p);
    EXPECT_GT(dot(sp.ng, expectedNormal), 0.9999f);
    EXPECT_EQ(sp.material, ref.flat ? green : red);
    flat += ref.flat;
    inside += length(r.o) < 1.0f;
  }
  EXPECT_GT(checked, 600);
  EXPECT_GT(flat, 50);
  EXPECT_GT(inside, 100);
}

// --- Rays and shadows from inside ------------------------------------------------------------

TEST(Csg, RaysFromInsideAHollowFindTheInnerWallAndAreShadowed) {
  Scene s;
  int mat = addMaterial(s, diffuse(Color(0.5f)));
  addShape(s,
           csg(CsgOp::kDifference,
               {child(std::make_shared<Sphere>(1.0f)), child(std::make_shared<Sphere>(0.5f))}),
           Mat4::translate({2, 0, 0}), mat);
  s.finalize();
  auto accel = makeAccelerator("embree", s);
  Hit h;
  // From the centre of the hollow: the inner wall, whose outward normal points to the centre.
  ASSERT_TRUE(accel->intersect(ray({2, 0, 0}, {0, 1, 0}), h));
  EXPECT_FLOAT_EQ(h.t, 0.5f);
  EXPECT_LT(s.surface(ray({2, 0, 0}, {0, 1, 0}), h).ng.y, -0.999f);
  // From inside the wall: the outer surface.
  ASSERT_TRUE(accel->intersect(ray({2.75f, 0, 0}, {1, 0, 0}), h));
  EXPECT_FLOAT_EQ(h.t, 0.25f);
  // Shadow rays: a light outside is hidden from the hollow; nothing blocks inside the hollow.
  EXPECT_TRUE(accel->occluded(Ray{{2, 0, 0}, {0, 5, 0}, 0, 1}));
  EXPECT_FALSE(accel->occluded(Ray{{2, 0, 0}, {0, 0.4f, 0}, 0, 1}));
  EXPECT_FALSE(accel->occluded(Ray{{0, 5, 0}, {0, 1, 0}, 0, 1}));
}

// --- Nesting ---------------------------------------------------------------------------------

TEST(Csg, NestedTreesEqualTheirFlatForm) {
  // A - (B u C) == A - B - C, and (A n B) n C == A n B n C, for every ray.
  auto a = child(std::make_shared<Box>(), Mat4::scale(Vec3(1.2f)));
  auto b = child(std::make_shared<Sphere>(0.7f), Mat4::translate({0.8f, 0.5f, 0}));
  auto c =
      child(std::make_shared<Box>(Vec3(-0.3f), Vec3(0.3f)), Mat4::translate({-0.5f, -0.6f, 0.9f}));
  auto d = child(std::make_shared<Sphere>(1.5f), Mat4::translate({0.2f, 0, 0}));
  Csg nested(CsgOp::kDifference, {a, child(csg(CsgOp::kUnion, {b, c}), Mat4::identity())});
  Csg flat(CsgOp::kDifference, {a, b, c});
  Csg nestedI(CsgOp::kIntersection, {child(csg(CsgOp::kIntersection, {a, d})), b});
  Csg flatI(CsgOp::kIntersection, {a, d, b});
  int nonTrivial = 0;
  for (const Ray& r : rayFan(500, 4.0f, 1.5f)) {
    for (auto [x, y] : {std::pair{&nested, &flat}, std::pair{&nestedI, &flatI}}) {
      std::vector<Interval> u, v;
      x->intervals(r, u);
      y->intervals(r, v);
      ASSERT_EQ(u.size(), v.size());
      for (size_t i = 0; i < u.size(); ++i) {
        EXPECT_FLOAT_EQ(u[i].enter.t, v[i].enter.t);
        EXPECT_FLOAT_EQ(u[i].exit.t, v[i].exit.t);
        EXPECT_EQ(u[i].enter.normal, v[i].enter.normal);
      }
      nonTrivial += u.size() > 1;
    }
  }
  EXPECT_GT(nonTrivial, 20);  // rays that see the holes
}

// --- Half-spaces and bounds ------------------------------------------------------------------

TEST(Csg, HalfSpaceCutsASphereAndKeepsFiniteBounds) {
  auto cut = csg(CsgOp::kIntersection,
                 {child(std::make_shared<Sphere>(1.0f)), child(std::make_shared<Plane>())});
  EXPECT_TRUE(cut->bounded());
  EXPECT_EQ(cut->bounds().lo, Vec3(-1.0f));
  EXPECT_EQ(cut->bounds().hi, Vec3(1.0f));
  Hit h;
  ASSERT_TRUE(cut->intersect(ray({0.2f, 5, 0}, {0, -1, 0}), h));  // the flat top at y = 0
  EXPECT_FLOAT_EQ(h.t, 5.0f);
  EXPECT_EQ(h.normal, Vec3(0, 1, 0));
  ASSERT_TRUE(cut->intersect(ray({0, -5, 0}, {0, 1, 0}), h));  // the round bottom
  EXPECT_FLOAT_EQ(h.t, 4.0f);
  EXPECT_FALSE(cut->intersect(ray({0, 5, 0}, {1, 0, 0}), h));  // above the cut, parallel
  // A tilted half-space still combines: +Y turned -45 degrees about z is the solid y <= -x.
  auto tilted =
      csg(CsgOp::kIntersection,
          {child(std::make_shared<Sphere>(1.0f)),
           child(std::make_shared<Plane>(), Mat4::rotate(0, 0, -0.38268343f, 0.92387953f))});
  ASSERT_TRUE(tilted->intersect(ray({-0.3f, 5, 0}, {0, -1, 0}), h));
  EXPECT_NEAR(h.t, 4.7f, 1e-5f);
  EXPECT_NEAR(normalize(h.normal).x, 0.70710678f, 1e-5f);
}

TEST(Csg, BoundsFollowTheOperation) {
  auto s1 = child(std::make_shared<Sphere>(1.0f), Mat4::translate({-0.5f, 0, 0}));
  auto s2 = child(std::make_shared<Sphere>(1.0f), Mat4::translate({0.5f, 0, 0}));
  Csg i(CsgOp::kIntersection, {s1, s2}), u(CsgOp::kUnion, {s1, s2}),
      d(CsgOp::kDifference, {s1, s2});
  EXPECT_EQ(i.bounds().lo, Vec3(-0.5f, -1, -1));
  EXPECT_EQ(i.bounds().hi, Vec3(0.5f, 1, 1));
  EXPECT_EQ(u.bounds().lo, Vec3(-1.5f, -1, -1));
  EXPECT_EQ(u.bounds().hi, Vec3(1.5f, 1, 1));
  EXPECT_EQ(d.bounds().lo, Vec3(-1.5f, -1, -1));
  EXPECT_EQ(d.bounds().hi, Vec3(0.5f, 1, 1));
}

TEST(Csg, UnboundedResultsAreReportedByName) {
  auto ball = child(std::make_shared<Sphere>(1.0f), Mat4::identity(), -1, "ball");
  auto ground = child(std::make_shared<Plane>(), Mat4::identity(), -1, "ground");
  Csg u(CsgOp::kUnion, {ball, ground}, "island");
  EXPECT_FALSE(u.bounded());
  EXPECT_FALSE(u.bounds().finite());
  try {
    u.requireBounded();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "CSG node 'island' is unbounded (union with the unbounded child 'ground')");
  }
  EXPECT_FALSE(Csg(CsgOp::kDifference, {ground, ball}).bounded());
  EXPECT_FALSE(Csg(CsgOp::kIntersection, {ground, ground}).bounded());
  EXPECT_NO_THROW(Csg(CsgOp::kDifference, {ball, ground}).requireBounded());
  // An unbounded node is still a valid child: intersected with a ball it is finite again.
  auto island = std::make_shared<Csg>(CsgOp::kUnion, std::vector<CsgChild>{ball, ground}, "island");
  Csg clipped(CsgOp::kIntersection, {child(island), child(std::make_shared<Sphere>(2.0f))});
  EXPECT_TRUE(clipped.bounded());
  EXPECT_EQ(clipped.bounds().hi, Vec3(2.0f));
  EXPECT_THROW(Csg(CsgOp::kUnion, {}, "empty"), Error);
  EXPECT_THROW(csgOpFromName("xor"), Error);
  EXPECT_EQ(csgOpFromName("difference"), CsgOp::kDifference);
}

}  // namespace
}  // namespace tray

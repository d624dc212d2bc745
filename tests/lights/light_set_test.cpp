// Light sampling against closed forms: the irradiance that light samples estimate from
// emissive triangles equals Lambert's polygon formula with either light chooser, the sampled
// pdf is the one pdf() gives for MIS, the power chooser picks in proportion to power, and
// emitters are one-sided.
#include "lights/light_set.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sampler.h"
#include "tests/polygon_irradiance.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

/// One emissive triangle (counter-clockwise seen from below: it faces -y) at height 2.
uint32_t addTriangleLight(Scene& s, const Vec3& a, const Vec3& b, const Vec3& c, Color Le,
                          bool twoSided = false) {
  Material m = diffuse(Color(0.0f));
  m.emissive = Le;
  m.doubleSided = twoSided;
  TriangleMesh mesh;
  mesh.positions = {a, b, c};
  mesh.indices = {0, 1, 2};
  mesh.material = addMaterial(s, m);
  return addMeshInstance(s, addMesh(s, mesh), Mat4::identity());
}

TEST(LightSet, TriangleSamplesEstimateLambertsIrradianceWithTheirOwnPdf) {
  // Two triangles of radiance 1 and 3 facing down onto a receiver at the origin. The light
  // sample estimator sum L cos / pdf must give the sum of both closed forms: that checks the
  // solid-angle pdf, the choice by power (its pmf is part of pdf) and pdf() for MIS.
  Scene s;
  const std::vector<Vec3> left = {{-2, 2, -1}, {-1, 2, -1}, {-0.5f, 2, 1}};
  const std::vector<Vec3> right = {{0.5f, 2, -0.5f}, {1, 2, -1}, {1.5f, 2, 0.5f}};
  addTriangleLight(s, left[0], left[1], left[2], Color(1.0f));
  addTriangleLight(s, right[0], right[1], right[2], Color(3.0f));
  s.finalize();
  for (LightSamplerKind kind : {LightSamplerKind::kPower, LightSamplerKind::kBvh}) {
    const LightSet lights(s, kind);
    ASSERT_EQ(lights.size(), 2u);
    ASSERT_EQ(lights.triangleCount(), 2u);

    const Vec3 x(0.1f, 0, 0.2f), n(0, 1, 0);
    const double expected = polygonIrradiance(x, n, left) + 3 * polygonIrradiance(x, n, right);
    double sum = 0;
    int counts[2] = {0, 0};
    const int samples = 200000;
    for (int i = 0; i < samples; ++i) {
      Sampler u(0, uint32_t(i), 5);
      const float uLight = u.next1D();
      LightSample ls = lights.sample({x, n, false}, uLight, u.next2D());
      ASSERT_TRUE(ls.valid());
      const int light = ls.p.x < 0 ? 0 : 1;
      ++counts[light];
      EXPECT_NEAR(lights.pdf(light, {x, n, false}, ls.wi, ls.p, {0, -1, 0}), ls.pdf,
                  1e-4f * ls.pdf);
      sum += ls.L.x * std::max(0.0f, dot(n, ls.wi)) / ls.pdf;
    }
    EXPECT_NEAR(sum / samples, expected, 0.01 * expected);
    if (kind == LightSamplerKind::kBvh) continue;  // it weighs by the receiver, not by power
    // Power = radiance x area x pi: the pick frequencies follow it.
    const double areaL = 0.5 * length(cross(left[1] - left[0], left[2] - left[0]));
    const double areaR = 0.5 * length(cross(right[1] - right[0], right[2] - right[0]));
    EXPECT_NEAR(counts[1] / double(samples), 3 * areaR / (areaL + 3 * areaR), 0.01);
  }
}

TEST(LightSet, EmittersAreOneSidedUnlessDoubleSided) {
  for (bool twoSided : {false, true}) {
    Scene s;
    addTriangleLight(s, {-1, 2, -1}, {1, 2, -1}, {0, 2, 1}, Color(1.0f), twoSided);
    s.finalize();
    const LightSet lights(s);
    const Vec3 below(0, 0, 0), above(0, 4, 0);
    EXPECT_TRUE(lights.sample({below, {0, 1, 0}, false}, 0.3f, {0.4f, 0.6f}).valid());
    EXPECT_EQ(lights.sample({above, {0, -1, 0}, false}, 0.3f, {0.4f, 0.6f}).valid(), twoSided)
        << "doubleSided " << twoSided;
  }
}

TEST(LightSet, SamplableEmissiveShapesAreLightsOthersAreLeftToBsdfSampling) {
  // Spheres and boxes are sampled through the Shape interface; an infinite plane (and CSG)
  // has no area to sample, so BSDF sampling finds it alone (lightAt -1: MIS weight 1).
  Scene s;
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(1.0f);
  const int m = addMaterial(s, glow);
  const uint32_t sphere = addSphere(s, {0, 3, 0}, 0.5f, m);
  const uint32_t plane = addShape(s, std::make_shared<Plane>(), Mat4::identity(), m);
  const uint32_t box = addShape(s, std::make_shared<Box>(), Mat4::translate({3, 3, 0}), m);
  s.finalize();
  const LightSet lights(s);
  EXPECT_EQ(lights.size(), 2u);
  EXPECT_EQ(lights.lightAt(sphere, 0), 0);
  EXPECT_EQ(lights.lightAt(plane, 0), -1);
  EXPECT_EQ(lights.lightAt(box, 0), 1);
  EXPECT_NEAR(lights.light(1).power(), 24.0 * kPi, 1e-3);  // a 2-unit cube: area 24
}

TEST(LightSet, BoxSamplesEstimateLambertsIrradianceUnderANonUniformScale) {
  // The box [-1, 1]^3 scaled by (0.5, 0.25, 1) and lifted to y = 1.5: faces are chosen by
  // world area (core/shape.h areaScale), so the area pdf is uniform; the estimator must give
  // the facing faces' closed forms, and pdf() the sampled density.
  Scene s;
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(1.0f);
  const Mat4 toWorld = Mat4::translate({0, 1.5f, 0}) * Mat4::scale({0.5f, 0.25f, 1.0f});
  addShape(s, std::make_shared<Box>(), toWorld, addMaterial(s, glow));
  s.finalize();
  const LightSet lights(s);
  ASSERT_EQ(lights.size(), 1u);
  const Vec3 x(0.7f, 0, -0.4f), n(0, 1, 0);
  const float lo = 1.25f, hi = 1.75f, hx = 0.5f, hz = 1.0f;
  const std::vector<std::vector<Vec3>> faces = {
      {{-hx, lo, -hz}, {hx, lo, -hz}, {hx, lo, hz}, {-hx, lo, hz}},    // bottom, faces x
      {{hx, lo, -hz}, {hx, hi, -hz}, {hx, hi, hz}, {hx, lo, hz}}};     // +x, faces x
  double expected = 0;
  for (const auto& f : faces) expected += polygonIrradiance(x, n, f);
  double sum = 0;
  const int samples = 200000;
  for (int i = 0; i < samples; ++i) {
    Sampler u(0, uint32_t(i), 9);
    const float uLight = u.next1D();
    LightSample ls = lights.sample({x, n, false}, uLight, u.next2D());
    if (!ls.valid()) continue;  // a face turned away from x
    // The normal of the face the sample lies on: the axis the point sits at the extreme of.
    const Vec3 q = (ls.p - Vec3(0, 1.5f, 0)) / Vec3(hx, 0.25f, hz);
    const Vec3 aq = abs(q);
    Vec3 nl(0.0f);
    if (aq.x >= aq.y && aq.x >= aq.z) nl.x = q.x > 0 ? 1.0f : -1.0f;
    else if (aq.y >= aq.z) nl.y = q.y > 0 ? 1.0f : -1.0f;
    else nl.z = q.z > 0 ? 1.0f : -1.0f;
    EXPECT_NEAR(lights.pdf(0, {x, n, false}, ls.wi, ls.p, nl), ls.pdf, 1e-3f * ls.pdf);
    sum += ls.L.x * std::max(0.0f, dot(n, ls.wi)) / ls.pdf;
  }
  EXPECT_NEAR(sum / samples, expected, 0.01 * expected);
}

}  // namespace
}  // namespace tray

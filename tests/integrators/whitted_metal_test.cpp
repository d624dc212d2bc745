// Whitted's mirror term of a metal is tinted by its base colour: Fresnel-Schlick with F0 = base
// colour (glTF 2.0 appendix B), so a red metal reflects only red; a stated TRAY_materials_phong
// kr stays an untinted mirror.
#include <gtest/gtest.h>

#include <cmath>

#include "accel/registry.h"
#include "integrators/whitted.h"
#include "render/prepared_scene.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

/// A smooth metal sphere of radius 1 at the origin under a white sky of 1 (no other light).
Scene metalSphere(const Material& m) {
  Scene s;
  addSphere(s, Vec3(0.0f), 1.0f, addMaterial(s, m));
  s.environment.background = Color(1.0f);
  s.finalize();
  return s;
}

Material redMetal() {
  Material m;  // glTF defaults, hasPhong false: Phong derived by phongFromPbr
  m.baseColor = Color(1, 0, 0);
  m.metallic = 1;
  m.roughness = 0;
  m.phong = phongFromPbr(m);
  return m;
}

/// Whitted's radiance along a ray from (x0, y0, 5) straight down -Z onto the sphere.
Color radianceAt(const Scene& s, float x0, float y0) {
  const PreparedScene prepared(s, lookAt({0, 0, 5}, {0, 0, 0}), {8, 8});
  const RenderContext ctx = prepared.context(RenderSettings{});
  auto whitted = makeWhitted(ctx);
  Sampler sampler(0, 0, 0);
  RayStats stats;
  return whitted->Li(Ray{{x0, y0, 5}, {0, 0, -1}}, sampler, stats, nullptr);
}

TEST(WhittedMetal, RedMetalReflectsOnlyRed) {
  const Scene s = metalSphere(redMetal());
  // Head on (cos 1): F = F0 = (1, 0, 0) exactly; the sky is 1, the metal has no diffuse term.
  const Color head = radianceAt(s, 0, 0);
  EXPECT_NEAR(head.x, 1.0f, 1e-6f);
  EXPECT_EQ(head.y, 0.0f);
  EXPECT_EQ(head.z, 0.0f);
  // Off axis, at the point with normal (0.8, 0, 0.6): cos = 0.6, the reflected ray leaves
  // into the sky, and Schlick gives R = 1, G = B = (1 - 0.6)^5 = 0.01024.
  const Color side = radianceAt(s, 0.8f, 0);
  EXPECT_NEAR(side.x, 1.0f, 1e-5f);
  EXPECT_NEAR(side.y, std::pow(0.4, 5), 1e-5);
  EXPECT_NEAR(side.z, std::pow(0.4, 5), 1e-5);
}

TEST(WhittedMetal, StatedPhongMirrorStaysUntinted) {
  Material m = redMetal();
  m.hasPhong = true;  // TRAY_materials_phong: kr 0.85, white F0 (the default)
  m.phong = PhongParams();
  m.phong.diffuse = Color(0.0f);
  m.phong.reflectance = 0.85f;
  const Color c = radianceAt(metalSphere(m), 0.8f, 0);
  EXPECT_EQ(c.x, 0.85f);
  EXPECT_EQ(c.y, 0.85f);
  EXPECT_EQ(c.z, 0.85f);
}

TEST(WhittedMetal, DielectricsKeepNoMirrorTerm) {
  Material m = redMetal();
  m.metallic = 0;
  m.phong = phongFromPbr(m);
  EXPECT_EQ(m.phong.reflectance, 0.0f);  // the mapping gives mirrors to metals only
}

}  // namespace
}  // namespace tray

// The path tracer's lights end to end, against closed forms: KHR_lights_punctual point, spot
// (glTF's smooth cone falloff) and directional lights over a diffuse floor; one-sided emissive
// triangles; and non-finite values that are caught, counted and (--debug-nan) reported.
#include <gtest/gtest.h>

#include <cmath>

#include "accel/registry.h"
#include "integrators/path.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "tests/integrators/path_probe.h"
#include "tests/integrators/path_under_test.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr float kAlbedo = 0.6f;

/// Radiance reflected towards the viewer by the floor point `at` (y = 0, normal +y) of a
/// scene with a Lambert floor and the given light, at max depth 2 (direct light only). Delta
/// lights are sampled exactly, so one sample is the answer.
float floorRadiance(const PunctualLightDesc& light, const Vec3& at) {
  Scene s;
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), addMaterial(s, diffuse(Color(kAlbedo))));
  s.lights.push_back(light);
  s.finalize();
  PathProbe probe(s, 2);
  Sampler sampler(3, 0, 1);
  const Vec3 eye = at + Vec3(0.3f, 0.4f, 0.1f);
  return probe.Li(Ray{eye, normalize(at - eye)}, sampler).x;
}

TEST(PathLights, PointLightGivesInverseSquareCosineIrradiance) {
  const Vec3 at(0.5f, 0, 0.25f), pos(0, 2, 0);
  const float I = 5;
  const Vec3 d = pos - at;
  const double cosine = d.y / length(d), E = I * cosine / lengthSquared(d);
  EXPECT_NEAR(floorRadiance(pointLight(pos, Color(I)), at), kAlbedo / kPi * E, 1e-5);
}

TEST(PathLights, SpotLightFollowsTheGltfConeFalloff) {
  // KHR_lights_punctual: full intensity inside the inner cone, none outside the outer one, and
  // in between the square of the linear ramp in cos(angle) (the spec's reference code).
  PunctualLightDesc spot;
  spot.type = PunctualLightDesc::Type::kSpot;
  spot.position = {0, 2, 0};
  spot.direction = {0, -1, 0};
  spot.intensity = Color(5.0f);
  spot.innerConeAngle = 0.2f;
  spot.outerConeAngle = 0.5f;
  for (double angle : {0.1, 0.3, 0.35, 0.45, 0.6}) {
    const Vec3 at(float(2 * std::tan(angle)), 0, 0);
    const Vec3 d = spot.position - at;
    const double t =
        std::clamp((std::cos(angle) - std::cos(0.5)) / (std::cos(0.2) - std::cos(0.5)), 0.0, 1.0);
    const double E = 5 * t * t * (d.y / length(d)) / lengthSquared(d);
    EXPECT_NEAR(floorRadiance(spot, at), kAlbedo / kPi * E, 1e-5) << "angle " << angle;
  }
}

TEST(PathLights, DirectionalLightGivesCosineIrradiance) {
  PunctualLightDesc sun;
  sun.type = PunctualLightDesc::Type::kDirectional;
  sun.direction = normalize(Vec3(1, -2, 0.5f));
  sun.intensity = Color(3.0f);
  const double E = 3 * -sun.direction.y;
  EXPECT_NEAR(floorRadiance(sun, {0.2f, 0, -0.3f}), kAlbedo / kPi * E, 1e-5);
}

TEST(PathLights, EmissiveTrianglesShineFromTheirFrontUnlessDoubleSided) {
  // A quad facing down, seen from below (its front) and from above (its back): max depth 1,
  // emission only.
  for (bool twoSided : {false, true}) {
    Scene s;
    Material glow = diffuse(Color(0.0f));
    glow.emissive = Color(2.0f);
    glow.doubleSided = twoSided;
    uint32_t quad = addMesh(s, quadMesh(1.0f, addMaterial(s, glow)));
    addMeshInstance(s, quad, Mat4::scale({1, -1, 1}));  // the mirror flips it to face -y
    s.finalize();
    PathProbe probe(s, 1);
    Sampler sampler(0, 0, 1);
    Color front = probe.Li(Ray{{0.1f, -2, 0}, {0, 1, 0}}, sampler);
    Color back = probe.Li(Ray{{0.1f, 2, 0}, {0, -1, 0}}, sampler);
    EXPECT_EQ(front.x, 2.0f);
    EXPECT_EQ(back.x, twoSided ? 2.0f : 0.0f) << "doubleSided " << twoSided;
  }
}

TEST(PathLights, NonFiniteSamplesAreCountedDiscardedAndReportedWithDebugNan) {
  // A sphere whose emission is NaN (a broken input the loader would let through as a value):
  // every sample that sees it is dropped and counted; the film stays finite, and --debug-nan
  // names the pixel and the quantity.
  Scene s;
  Material broken = diffuse(Color(0.5f));
  broken.emissive = Color(std::nanf(""));
  addSphere(s, {0, 0, 0}, 1.0f, addMaterial(s, broken));
  s.environment.background = Color(0.5f);
  s.finalize();
  for (bool debug : {false, true}) {
    RenderSettings st;
    st.set("integrator", test::pathUnderTest());
    st.set("spp", 2);
    st.set("debug-nan", debug);
    const PreparedScene prepared(s, lookAt({0, 0, 4}, {0, 0, 0}, 0.6f), {8, 8});
    const RenderContext ctx = prepared.context(st);
    auto integrator = makeIntegrator(ctx);
    Film film(8, 8);
    ::testing::internal::CaptureStderr();
    RenderStats stats = renderImage(*integrator, film, RenderOptions{});
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_GT(stats.rays.nanSamples, 0u);
    EXPECT_LT(stats.rays.nanSamples, 8u * 8u * 2u);  // the background's samples are fine
    for (float v : film.layers()[0].data) EXPECT_TRUE(std::isfinite(v));
    if (debug) {
      EXPECT_NE(err.find("debug-nan: pixel ("), std::string::npos) << err;
      EXPECT_NE(err.find("non-finite emission"), std::string::npos) << err;
    } else {
      EXPECT_EQ(err.find("debug-nan"), std::string::npos) << err;
    }
  }
}

}  // namespace
}  // namespace tray

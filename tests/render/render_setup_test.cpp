// Default lighting: an unlit glTF asset (most Khronos samples) must not render black, and a
// scene with any light of its own must be left alone.
#include "render/render_setup.h"

#include <gtest/gtest.h>

#include <optional>

#include "accel/registry.h"
#include "integrators/registry.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

Scene unlitSphereScene() {
  Scene s;
  addSphere(s, Vec3(0.0f), 1.0f, addMaterial(s, diffuse(Color(0.5f))));
  s.finalize();
  return s;
}

TEST(DefaultLighting, AddsAHeadlightToAnUnlitScene) {
  Scene s = unlitSphereScene();
  const CameraDesc cam = lookAt(Vec3(0, 0, 5), Vec3(0.0f));
  ASSERT_TRUE(addDefaultLightingIfUnlit(s, cam));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, PunctualLightDesc::Type::kDirectional);
  // The light travels away from the camera (forward = -Z here), so the side the camera sees
  // is lit; and from above (it travels downwards).
  EXPECT_LT(s.lights[0].direction.z, -0.5f);
  EXPECT_LT(s.lights[0].direction.y, 0.0f);
  EXPECT_NEAR(length(s.lights[0].direction), 1.0f, 1e-5f);
  EXPECT_FLOAT_EQ(s.environment.background.x, 0.1f);
  // Twice is once: the scene is lit now.
  EXPECT_FALSE(addDefaultLightingIfUnlit(s, cam));
  EXPECT_EQ(s.lights.size(), 1u);
}

TEST(DefaultLighting, LeavesLitScenesAlone) {
  const CameraDesc cam = lookAt(Vec3(0, 0, 5), Vec3(0.0f));
  Scene withLight = unlitSphereScene();
  withLight.lights.push_back(pointLight(Vec3(0, 5, 0), Color(10.0f)));
  EXPECT_FALSE(addDefaultLightingIfUnlit(withLight, cam));
  EXPECT_EQ(withLight.lights.size(), 1u);

  Scene withEnvironment = unlitSphereScene();
  withEnvironment.environment.background = Color(0.5f);
  EXPECT_FALSE(addDefaultLightingIfUnlit(withEnvironment, cam));
  EXPECT_TRUE(withEnvironment.lights.empty());

  Scene withEmitter = unlitSphereScene();
  withEmitter.materials[0].emissive = Color(1.0f);
  EXPECT_FALSE(addDefaultLightingIfUnlit(withEmitter, cam));
  EXPECT_TRUE(withEmitter.lights.empty());
}

/// A 10 x 10 floor (area 100) and a 1 x 1 quad (area 1) above it whose emission is the
/// factor times an emissive texture: `lit` of its 64 x 64 texels are 1, the rest black.
Scene floorWithTexturedEmitter(float factor, int lit) {
  Scene s;
  addMeshInstance(s, addMesh(s, quadMesh(5.0f, addMaterial(s, diffuse(Color(0.5f))))),
                  Mat4::identity());
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(factor);
  TextureImage t;
  t.width = t.height = 64;
  t.pixels.assign(64 * 64 * 3, 0.0f);
  for (int i = 0; i < 3 * lit; ++i) t.pixels[size_t(i)] = 1.0f;
  s.textures.push_back(t);
  glow.emissiveTexture.image = 0;
  addMeshInstance(s, addMesh(s, quadMesh(0.5f, addMaterial(s, glow))), Mat4::translate({0, 1, 0}));
  s.finalize();
  return s;
}

TEST(DefaultLighting, DecidesByEmittedPowerNotByAnEmissiveTexture) {
  // A car whose emissive texture is black but for its lamps counted as lit and rendered black.
  // Threshold: 1% of 2.5 x 101 / 4 = 0.63 W; the quad gives pi x factor x lit/4096.
  const CameraDesc cam = lookAt(Vec3(0, 5, 5), Vec3(0.0f));
  Scene lamps = floorWithTexturedEmitter(4.0f, 10);  // 0.031 W (bright lamps, mostly black)
  EXPECT_FALSE(summarizeEmission(lamps).meaningful());
  EXPECT_NEAR(summarizeEmission(lamps).meshPower, kPi * 4 * 10 / 4096, 1e-6);
  EXPECT_NEAR(summarizeEmission(lamps).surfaceArea, 101.0, 1e-3);
  EXPECT_TRUE(addDefaultLightingIfUnlit(lamps, cam));

  Scene panel = floorWithTexturedEmitter(5.0f, 4096);  // 15.7 W: a real light panel
  EXPECT_TRUE(summarizeEmission(panel).meaningful());
  EXPECT_FALSE(addDefaultLightingIfUnlit(panel, cam));
}

TEST(DefaultLighting, CoreGltfGlowIsNotTheScenesLight) {
  // ClearCoatTest, TextureEncodingTest, TextureTransformMultiTest: white emissive labels
  // (factor 1, radiance 1) passed the power rule, so no default light came, and the spheres
  // and cubes they label rendered black. Core glTF emission cannot exceed radiance 1: such
  // surfaces glow like screens; only a stronger emitter (emissive_strength) is a light.
  const CameraDesc cam = lookAt(Vec3(0, 5, 5), Vec3(0.0f));
  Scene labels = floorWithTexturedEmitter(1.0f, 4096);  // pi W: past the 0.63 W power rule
  EXPECT_FALSE(summarizeEmission(labels).meaningful());
  EXPECT_TRUE(addDefaultLightingIfUnlit(labels, cam));
  Scene bright = floorWithTexturedEmitter(1.001f, 4096);
  EXPECT_TRUE(summarizeEmission(bright).meaningful());
}

// The glow rule is about meshes: an analytic shape sharing the glowing mesh's material is still
// a light, whichever of the two comes first.
TEST(DefaultLighting, AShapeSharingAGlowMaterialStillCounts) {
  Scene s;
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(1.0f);
  const int m = addMaterial(s, glow);
  addMeshInstance(s, addMesh(s, quadMesh(0.5f, m)), Mat4::identity());
  addSphere(s, Vec3(0, 2, 0), 0.5f, m);
  s.finalize();
  EXPECT_TRUE(summarizeEmission(s).emissiveShapes);
  EXPECT_EQ(summarizeEmission(s).meshPower, 0.0);
  EXPECT_FALSE(addDefaultLightingIfUnlit(s, lookAt(Vec3(0, 0, 5), Vec3(0.0f))));
}

TEST(DefaultLighting, UnusedEmissiveMaterialsDoNotCount) {
  Scene s = unlitSphereScene();
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(100.0f);
  addMaterial(s, glow);  // in the file, on no object
  EXPECT_TRUE(addDefaultLightingIfUnlit(s, lookAt(Vec3(0, 0, 5), Vec3(0.0f))));
}

/// The unlit sphere inside a closed 40 x 40 x 40 box of diffuse triangles: a sky box. With
/// `sky`, the box is KHR_materials_unlit of that colour, as sky boxes in assets are.
Scene sphereInSkyBox(std::optional<Color> sky = std::nullopt) {
  Scene s = unlitSphereScene();
  TriangleMesh box;
  const float h = 20;
  for (int i = 0; i < 8; ++i)
    box.positions.push_back({i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h});
  // Two triangles per face; the winding does not matter to occlusion.
  box.indices = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                 2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
  Material boxMaterial = diffuse(Color(0.5f));
  if (sky) {
    boxMaterial.unlit = true;
    boxMaterial.baseColor = *sky;
  }
  box.material = addMaterial(s, boxMaterial);
  addMeshInstance(s, addMesh(s, box), Mat4::identity());
  s.finalize();
  return s;
}

/// The centre pixel's red channel, direct light only (max depth 2).
float centrePixel(const Scene& s, const CameraDesc& cam) {
  RenderSettings settings;
  settings.set("integrator", "path");
  settings.set("spp", 16);
  settings.set("max-depth", 2);
  const Film film = renderFilm(s, cam, 33, 33, settings, nullptr, {}, "embree", 2);
  return film.pixel(Film::kBeauty, 16, 16)[0];
}

TEST(DefaultLighting, AHeadlightReplacesTheKeyLightWhenASkyBoxEnclosesTheCamera) {
  Scene s = sphereInSkyBox();
  const CameraDesc cam = lookAt(Vec3(0, 0, 5), Vec3(0.0f));
  ASSERT_TRUE(addDefaultLightingIfUnlit(s, cam));
  // The sky box keeps out both the key light and the environment: a black sphere.
  EXPECT_EQ(centrePixel(s, cam), 0.0f);
  auto accel = makeAccelerator("embree", s);
  ASSERT_TRUE(useHeadlightIfEnclosed(s, cam, *accel));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, PunctualLightDesc::Type::kPoint);
  // The sphere's nearest point, 4 from the camera, receives the key light's irradiance: a
  // Lambertian albedo 0.5 facing the light sends 0.5 / pi x 2.5 back.
  const float expected = 0.5f / kPi * EmissionSummary::kDefaultIrradiance;
  EXPECT_NEAR(centrePixel(s, cam), expected, 0.02f * expected);
}

TEST(DefaultLighting, AnUnlitSkyBoxLightsTheSceneInsteadOfTheDefaultLight) {
  // Before: the headlight replaced the key light and added to the sky's own light (assets
  // came out blown out). Now the unlit box is the light, as the sky it stands for.
  const Color sky(0.8f, 0.6f, 0.4f);
  Scene s = sphereInSkyBox(sky);
  const CameraDesc cam = lookAt(Vec3(0, 0, 5), Vec3(0.0f));
  ASSERT_TRUE(addDefaultLightingIfUnlit(s, cam));
  auto accel = makeAccelerator("embree", s);
  ASSERT_TRUE(useUnlitEnclosureAsLight(s, cam, *accel));
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(s.environment.ambient.x, 0.0f);
  // A convex Lambertian of albedo 0.5 inside a uniform sky of radiance c sends 0.5 c back
  // (one bounce: the sky is found by the BSDF sample, with no light sampling of it).
  EXPECT_NEAR(centrePixel(s, cam), 0.5f * sky.x, 0.03f * 0.5f * sky.x);
}

TEST(DefaultLighting, ADiffuseOrBlackEnclosureIsNotASky) {
  for (const auto& box : {sphereInSkyBox(), sphereInSkyBox(Color(0.0f))}) {
    Scene s = box;
    const CameraDesc cam = lookAt(Vec3(0, 0, 5), Vec3(0.0f));
    ASSERT_TRUE(addDefaultLightingIfUnlit(s, cam));
    auto accel = makeAccelerator("embree", s);
    EXPECT_TRUE(cameraEnclosed(cam, *accel));
    EXPECT_FALSE(useUnlitEnclosureAsLight(s, cam, *accel));
    EXPECT_EQ(s.lights.size(), 1u);  // left for the headlight
  }
}

TEST(DefaultLighting, OnlyIntegratorsThatGatherFromUnlitSurfacesUseTheSky) {
  RenderSettings settings;
  for (const char* name : {"path", "path-scalar", "bdpt"}) {
    settings.set("integrator", name);
    EXPECT_TRUE(unlitSurfacesLight(settings)) << name;
  }
  for (const char* name : {"whitted", "sppm"}) {
    settings.set("integrator", name);
    EXPECT_FALSE(unlitSurfacesLight(settings)) << name;
  }
  settings.set("integrator", "adaptive");  // its inner integrator (whitted by default) decides
  EXPECT_FALSE(unlitSurfacesLight(settings));
  settings.set("inner", "path");
  EXPECT_TRUE(unlitSurfacesLight(settings));
}

TEST(DefaultLighting, TheKeyLightStaysWhereItCanReachTheScene) {
  Scene s = unlitSphereScene();
  const CameraDesc cam = lookAt(Vec3(0, 0, 5), Vec3(0.0f));
  ASSERT_TRUE(addDefaultLightingIfUnlit(s, cam));
  auto accel = makeAccelerator("embree", s);
  EXPECT_FALSE(useHeadlightIfEnclosed(s, cam, *accel));
  EXPECT_EQ(s.lights[0].type, PunctualLightDesc::Type::kDirectional);
  EXPECT_GT(centrePixel(s, cam), 0.1f);
}

}  // namespace
}  // namespace tray

namespace tray {
namespace {

TEST(ImageSize, AnOrthographicCameraGivesItsExtentsAspect) {
  CameraDesc c;
  c.type = CameraDesc::Type::kOrthographic;
  c.xmag = 2.5f, c.ymag = 2.5f;
  EXPECT_EQ(resolveImageSize("", c).height, 640);  // square extents: a square image
  c.xmag = 4.0f, c.ymag = 1.0f;
  EXPECT_EQ(resolveImageSize("", c).height, 160);
  c.type = CameraDesc::Type::kPerspective;  // without aspectRatio: 4:3, as before
  EXPECT_EQ(resolveImageSize("", c).height, 480);
  EXPECT_EQ(resolveImageSize("30x20", c).height, 20);
}

}  // namespace
}  // namespace tray

// Default lighting: an unlit glTF asset (most Khronos samples) must not render black, and a
// scene with any light of its own must be left alone.
#include "core/render_setup.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace tray

// render/ray_range.h: the camera and lights a scene would make rays from are refused at load,
// one line naming them, when a coordinate is NaN, infinite or beyond 1e17 (issue 40: Embree
// aborted the process on such rays); the largest values in range still render.
#include "render/ray_range.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "core/error.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

std::string refusal(const Scene& scene, const CameraDesc& camera) {
  try {
    checkRayRange("far.gltf", scene, camera);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(RayRange, RefusesCamerasAndLightsBeyondTheTracersRange) {
  Scene scene;
  CameraDesc camera = test::lookAt({0, 0, 5}, {0, 0, 0});
  camera.name = "cam";
  EXPECT_EQ(refusal(scene, camera), "");
  struct Case {
    void (*change)(Scene&, CameraDesc&);
    const char* says;
  } cases[] = {
      {[](Scene&, CameraDesc& c) { c.toWorld = Transform(Mat4::translate({1e19f, 0, 0})); },
       "the camera 'cam' is at"},
      {[](Scene&, CameraDesc& c) { c.motion = {Mat4(), Mat4::translate({0, -3e18f, 0})}; },
       "the camera 'cam' moves to"},
      {[](Scene&, CameraDesc& c) { c.lensRadius = 1e19f; }, "lens radius"},
      {[](Scene&, CameraDesc& c) { c.focusDistance = std::numeric_limits<float>::infinity(); },
       "focus distance"},
      {[](Scene&, CameraDesc& c) { c.xmag = 1e30f; }, "orthographic xmag"},
      {[](Scene&, CameraDesc& c) { c.znear = std::numeric_limits<float>::quiet_NaN(); }, "znear"},
      {[](Scene& s, CameraDesc&) { s.lights.push_back(test::pointLight({0, 2e18f, 0}, Color(1))); },
       "punctual light 0 is at"},
  };
  for (const Case& c : cases) {
    Scene s = scene;
    CameraDesc cd = camera;
    c.change(s, cd);
    const std::string said = refusal(s, cd);
    EXPECT_NE(said.find(c.says), std::string::npos) << said;
    EXPECT_EQ(said.rfind("far.gltf: ", 0), 0u) << said;
    EXPECT_NE(said.find("1e17"), std::string::npos) << said;
  }
  // A directional light has no position; the bound itself is in range.
  Scene sun;
  sun.lights.push_back(test::directionalLight({0, -1, 0}, Color(1)));
  sun.lights.back().position = Vec3(1e30f);
  CameraDesc edge = camera;
  edge.toWorld = Transform(Mat4::translate({kMaxRayCoordinate, 0, 0}));
  edge.lensRadius = kMaxRayCoordinate;
  EXPECT_EQ(refusal(sun, edge), "");
}

}  // namespace
}  // namespace tray

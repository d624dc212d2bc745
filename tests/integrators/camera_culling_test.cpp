// glTF's back-face culling for camera rays (core/camera_culling.h): the camera sees through the
// back of a single-sided surface to what lies beyond, in every integrator and on both
// accelerators; a double-sided surface stays; secondary rays still see both faces.
#include "core/camera_culling.h"

#include <gtest/gtest.h>

#include <cmath>

#include "accel/registry.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

/// A grey sphere at the origin, a point light beside it, and (unless `noPanel`) a 1 x 1 panel
/// between it and the camera at z = 2, its front face turned away from the camera (towards the
/// sphere) unless `facingCamera`.
Scene panelScene(bool noPanel, bool doubleSided, bool facingCamera = false) {
  Scene s;
  addSphere(s, Vec3(0.0f), 1.0f, addMaterial(s, diffuse(Color(0.5f))));
  if (!noPanel) {
    Material red = diffuse(Color(0.9f, 0.0f, 0.0f));
    red.doubleSided = doubleSided;
    const float q = std::sqrt(0.5f);  // a quarter turn about x: the quad's +Y front to -Z or +Z
    const Mat4 place =
        Mat4::translate(Vec3(0, 0, 2)) * Mat4::rotate(facingCamera ? q : -q, 0, 0, q);
    addMeshInstance(s, addMesh(s, quadMesh(0.5f, addMaterial(s, red))), place);
  }
  s.lights.push_back(pointLight(Vec3(3, 0, 1.5f), Color(20.0f)));
  s.finalize();
  return s;
}

const CameraDesc kCamera = lookAt(Vec3(0, 0, 5), Vec3(0.0f), 0.3f);

Color centre(const Scene& s, const char* integrator, const char* accel = "embree") {
  RenderSettings settings;
  settings.set("integrator", integrator);
  settings.set("spp", 4);
  if (std::string(integrator) != "whitted") settings.set("max-depth", 2);  // direct light only
  if (std::string(integrator) == "sppm") settings.set("photons", 20000);
  const Film film = renderFilm(s, kCamera, 9, 9, settings, nullptr, {}, accel, 2);
  const float* p = film.pixel(Film::kBeauty, 4, 4);
  return Color(p[0], p[1], p[2]);
}

TEST(CameraCulling, TheFaceTest) {
  const Scene away = panelScene(false, false), toward = panelScene(false, false, true);
  auto accel = makeAccelerator("embree", away);
  const Ray ray{Vec3(0, 0, 5), Vec3(0, 0, -1)};
  Hit hit;
  ASSERT_TRUE(accel->intersect(ray, hit));
  EXPECT_NEAR(hit.t, 3.0f, 1e-4f);  // the panel
  EXPECT_TRUE(cameraCulls(away, ray, hit));
  Hit beyond;
  ASSERT_TRUE(intersectCameraRay(*accel, away, ray, beyond));
  EXPECT_NEAR(beyond.t, 4.0f, 1e-4f);  // the sphere
  auto accelToward = makeAccelerator("embree", toward);
  ASSERT_TRUE(intersectCameraRay(*accelToward, toward, ray, hit));
  EXPECT_NEAR(hit.t, 3.0f, 1e-4f);  // its front: seen
}

TEST(CameraCulling, AMirroringPlacementFlipsTheFrontFace) {
  // glTF 2.0 3.7.2.1: a negative determinant makes the clockwise face the front. Mirrored in z,
  // the flat panel has the same world vertices and winding as the culled one, but its front
  // now faces the camera.
  Scene s = panelScene(true, false);
  const float q = std::sqrt(0.5f);
  const Mat4 mirrored = Mat4::translate(Vec3(0, 0, 2)) * Mat4::scale(Vec3(1, 1, -1)) *
                        Mat4::rotate(-q, 0, 0, q);
  Material red = diffuse(Color(0.9f, 0.0f, 0.0f));
  addMeshInstance(s, addMesh(s, quadMesh(0.5f, addMaterial(s, red))), mirrored);
  s.finalize();
  auto accel = makeAccelerator("embree", s);
  Hit hit;
  ASSERT_TRUE(intersectCameraRay(*accel, s, Ray{Vec3(0, 0, 5), Vec3(0, 0, -1)}, hit));
  EXPECT_NEAR(hit.t, 3.0f, 1e-4f);  // seen
}

TEST(CameraCulling, EveryIntegratorSeesThroughASingleSidedBack) {
  const Scene culled = panelScene(false, false), open = panelScene(true, false),
              kept = panelScene(false, true);
  for (const char* integrator : {"path", "path-scalar", "whitted", "bdpt", "sppm"}) {
    const Color through = centre(culled, integrator), bare = centre(open, integrator);
    ASSERT_GT(bare.y, 0.01f) << integrator;  // the sphere is lit where the camera looks
    // The sphere as without the panel (which does not shadow that point), up to noise.
    EXPECT_NEAR(through.y, bare.y, 0.1f * bare.y) << integrator;
    // Double-sided, the panel's back (unlit from there) hides the sphere.
    EXPECT_LT(centre(kept, integrator).y, 0.1f * bare.y) << integrator;
  }
  for (const char* accel : {"embree", "bvh"})
    EXPECT_EQ(centre(culled, "path", accel).y, centre(culled, "path-scalar", accel).y) << accel;
}

TEST(CameraCulling, SecondaryRaysStillSeeBothFaces) {
  // The light behind the panel (as seen from the sphere's front): the culled panel still
  // casts its shadow, so single-sided walls do not leak light.
  Scene s = panelScene(false, false);
  s.lights[0] = pointLight(Vec3(0, 0, 4), Color(20.0f));
  s.finalize();
  Scene open = panelScene(true, false);
  open.lights[0] = s.lights[0];
  open.finalize();
  EXPECT_GT(centre(open, "path").y, 0.05f);
  EXPECT_EQ(centre(s, "path").y, 0.0f);
}

}  // namespace
}  // namespace tray

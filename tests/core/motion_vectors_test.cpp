// Motion vectors (core/motion_vectors.h, docs/aovs.md "Motion vectors"): for a rigid animation
// seen by a moving camera, each pixel's vector takes its first hit back to where the previous
// frame's camera saw that point of the object, computed here from the pinhole model directly.
#include "core/motion_vectors.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/render_film.h"
#include "tests/scene_builder.h"
#include "tests/shapes/solid_meshes.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr int kW = 64, kH = 48;

/// Raster position (x right, y down) of world point p through a perspective camera, from the
/// pinhole model: camera space by the inverse placement, then x / -z and y / -z against the
/// half-field tangents (the image's aspect sets the horizontal one).
Vec2 pinhole(const CameraDesc& c, const Transform& toWorld, const Vec3& p) {
  const Vec3 q = toWorld.inversePoint(p);
  const double ty = std::tan(0.5 * c.yfov), tx = ty * kW / kH;
  return {float(0.5 * kW * (1 + q.x / (-q.z) / tx)), float(0.5 * kH * (1 - q.y / (-q.z) / ty))};
}

struct Shot {
  Scene scene;
  CameraDesc camera;
  Mat4 boxNow, boxBefore;
};

/// A box turning and moving, a static sphere and floor, and a camera that moved too.
Shot rigidShot() {
  Shot s;
  const int grey = addMaterial(s.scene, diffuse(Color(0.6f)));
  s.boxNow = Mat4::translate({0.3f, 0.5f, 0}) * Mat4::rotate(0, 0.1736482f, 0, 0.9848078f);
  s.boxBefore = Mat4::translate({0.1f, 0.45f, 0.1f}) * Mat4::rotate(0, 0.0436194f, 0, 0.9990482f);
  addMeshInstance(s.scene, addMesh(s.scene, boxMesh(Vec3(-0.3f), Vec3(0.3f), grey)), s.boxNow);
  addSphere(s.scene, {-0.6f, 0.3f, 0.2f}, 0.3f, grey);
  addMeshInstance(s.scene, addMesh(s.scene, quadMesh(3, grey)), Mat4());
  s.scene.lights.push_back(pointLight({1, 3, 2}, Color(20.0f)));
  s.scene.previousToWorld = {s.boxBefore, s.scene.primitives[1].toWorld.m, Mat4()};
  s.scene.finalize();
  s.camera = lookAt({0, 1.2f, 3.5f}, {0, 0.4f, 0});
  s.camera.previousToWorld = lookAt({0.25f, 1.1f, 3.6f}, {0, 0.45f, 0}).toWorld;
  return s;
}

TEST(MotionVectors, ReprojectThePreviousFramesPositions) {
  const Shot shot = rigidShot();
  RenderSettings settings;
  settings.set("spp", 1);  // position and ids are the first sample's: the vector's own hit
  const Film film = renderFilm(shot.scene, shot.camera, kW, kH, settings, nullptr,
                               {"motion", "position", "objectid"});
  const int motion = film.findLayer("motion"), position = film.findLayer("P"),
            id = film.findLayer("objectid");
  ASSERT_GE(motion, 0);
  Mat4 nowInv;
  ASSERT_TRUE(invert(shot.boxNow, nowInv));
  double worst = 0;
  int box = 0, still = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float* uv = film.pixel(motion, x, y);
      const int object = int(film.pixel(id, x, y)[0]);
      if (object < 0) {
        EXPECT_EQ(uv[0], 0.0f);
        EXPECT_EQ(uv[1], 0.0f);
        continue;
      }
      const float* pp = film.pixel(position, x, y);
      const Vec3 p{pp[0], pp[1], pp[2]};
      Transform before;
      before.m = object == 0 ? shot.boxBefore * nowInv : Mat4();
      const Vec2 now = pinhole(shot.camera, shot.camera.toWorld, p);
      const Vec2 then = pinhole(shot.camera, *shot.camera.previousToWorld, before.point(p));
      // u right, v up: this frame's position minus the previous frame's.
      worst = std::max({worst, std::fabs(double(uv[0]) - (now.x - then.x)),
                        std::fabs(double(uv[1]) - (then.y - now.y))});
      box += object == 0;
      still += object != 0;
    }
  std::printf("motion vectors: worst error %.2e px over %d box and %d static pixels\n", worst, box,
              still);
  EXPECT_LT(worst, 0.01);
  EXPECT_GT(box, 50);
  EXPECT_GT(still, 500);
}

TEST(MotionVectors, ZeroWhereNothingMoves) {
  Shot shot = rigidShot();
  shot.scene.previousToWorld = {shot.boxNow, shot.scene.primitives[1].toWorld.m, Mat4()};
  shot.camera.previousToWorld.reset();
  const Film film =
      renderFilm(shot.scene, shot.camera, kW, kH, RenderSettings(), nullptr, {"motion"});
  const int motion = film.findLayer("motion");
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      EXPECT_EQ(film.pixel(motion, x, y)[0], 0.0f);
      EXPECT_EQ(film.pixel(motion, x, y)[1], 0.0f);
    }
}

}  // namespace
}  // namespace tray

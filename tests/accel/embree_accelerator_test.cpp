#include <gtest/gtest.h>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "core/error.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

/// Two spheres on the z axis and one quad mesh instanced twice (at z = -6 and z = -8).
Scene lineOfObjects() {
  Scene s;
  int m = addMaterial(s, diffuse(Color(0.5f)));
  addSphere(s, {0, 0, -2}, 0.5f, m);
  addSphere(s, {0, 0, -4}, 0.5f, m);
  uint32_t quad = addMesh(s, quadMesh(1.0f, m));
  // Rotate the y = 0 quad to face +Z: x stays, y -> z.
  Mat4 faceZ = Mat4::rotate(std::sin(kPi / 4), 0, 0, std::cos(kPi / 4));
  addMeshInstance(s, quad, Mat4::translate({0, 0, -6}) * faceZ);
  addMeshInstance(s, quad, Mat4::translate({0, 0, -8}) * faceZ);
  s.finalize();
  return s;
}

TEST(EmbreeAccelerator, ClosestHitIsNearestPrimitive) {
  Scene s = lineOfObjects();
  auto accel = makeAccelerator("embree", s);
  Hit h;
  ASSERT_TRUE(accel->intersect(Ray{{0, 0, 0}, {0, 0, -1}}, h));
  EXPECT_EQ(h.primitive, 0u);
  EXPECT_NEAR(h.t, 1.5f, 1e-5f);
  ASSERT_TRUE(accel->intersect(Ray{{0, 0, -5}, {0, 0, -1}}, h));  // past the spheres
  EXPECT_EQ(h.primitive, 2u);
  EXPECT_NEAR(h.t, 1.0f, 1e-5f);
  SurfacePoint sp = s.surface(Ray{{0, 0, -5}, {0, 0, -1}}, h);
  EXPECT_NEAR(std::fabs(sp.ng.z), 1.0f, 1e-5f);
  EXPECT_NEAR(sp.p.z, -6.0f, 1e-5f);
}

TEST(EmbreeAccelerator, MeshIsBuiltOnceAndInstanced) {
  Scene s = lineOfObjects();
  EXPECT_EQ(s.meshes.size(), 1u);
  auto accel = makeAccelerator("embree", s);
  Hit h;
  ASSERT_TRUE(accel->intersect(Ray{{0.5f, 0.5f, -7}, {0, 0, -1}}, h));
  EXPECT_EQ(h.primitive, 3u);  // the second instance
}

TEST(EmbreeAccelerator, OcclusionRespectsRange) {
  Scene s = lineOfObjects();
  auto accel = makeAccelerator("embree", s);
  EXPECT_TRUE(accel->occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 2.0f}));
  EXPECT_FALSE(accel->occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 1.4f}));
  EXPECT_FALSE(accel->occluded(Ray{{0, 0, 0}, {0, 0, 1}}));
}

TEST(EmbreeAccelerator, AllHitsSortedIncludingSphereExits) {
  Scene s = lineOfObjects();
  auto accel = makeAccelerator("embree", s);
  std::vector<Hit> hits;
  accel->allHits(Ray{{0.1f, 0.1f, 0}, {0, 0, -1}}, hits);
  // Each sphere twice (enter, exit), each quad once.
  ASSERT_EQ(hits.size(), 6u);
  for (size_t i = 1; i < hits.size(); ++i) EXPECT_LT(hits[i - 1].t, hits[i].t);
  EXPECT_EQ(hits[0].primitive, 0u);
  EXPECT_EQ(hits[1].primitive, 0u);
  EXPECT_EQ(hits[4].primitive, 2u);
  EXPECT_EQ(hits[5].primitive, 3u);
  // Range limits apply.
  accel->allHits(Ray{{0.1f, 0.1f, 0}, {0, 0, -1}, 0.0f, 3.0f}, hits);
  EXPECT_EQ(hits.size(), 2u);
}

TEST(EmbreeAccelerator, InfinitePlaneIsHitFarAway) {
  Scene s;
  int m = addMaterial(s, diffuse(Color(0.5f)));
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), m);
  s.finalize();
  auto accel = makeAccelerator("embree", s);
  Hit h;
  ASSERT_TRUE(accel->intersect(Ray{{1e6f, 10, 0}, {0, -1, 0}}, h));
  EXPECT_FLOAT_EQ(h.t, 10.0f);
  EXPECT_FALSE(accel->intersect(Ray{{0, 10, 0}, {1, 0, 0}}, h));
}

TEST(EmbreeAccelerator, UnknownNameIsAnError) {
  Scene s;
  s.finalize();
  EXPECT_THROW(makeAccelerator("octree", s), Error);
}

}  // namespace
}  // namespace tray

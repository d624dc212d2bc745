// Moving primitives on every accelerator against Embree's own motion blur (instance motion and
// user geometry over time steps): the same closest hits, occlusion and surface points at random
// ray times, and the same image from the path tracer. docs/scene-format.md, "Motion blur".
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "accel/registry.h"
#include "core/motion.h"
#include "tests/accel/batch_test_scenes.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"
#include "tests/shapes/solid_meshes.h"

namespace tray {
namespace {

using namespace tray::test;

/// A cube mesh turning and rising over three steps, a sphere (user geometry) moving along x
/// over two, a static sphere and a floor, and a quad whose vertices move (a deforming mesh,
/// TriangleMesh::positionSteps): motion of every kind beside static primitives.
Scene movingScene() {
  Scene s;
  const int grey = addMaterial(s, diffuse(Color(0.6f)));
  const int red = addMaterial(s, diffuse(Color(0.8f, 0.2f, 0.2f)));
  addMovingCubeAndBall(s, red, grey);
  addSphere(s, {0, 0.3f, -1}, 0.3f, grey);
  addMeshInstance(s, addMesh(s, quadMesh(3, grey)), Mat4());
  TriangleMesh flag;
  flag.positions = {
      {-0.3f, 0.9f, -0.8f}, {0.3f, 0.9f, -0.8f}, {0.3f, 1.1f, -0.8f}, {-0.3f, 1.1f, -0.8f}};
  flag.indices = {0, 1, 2, 0, 2, 3};
  flag.material = red;
  flag.positionSteps = {flag.positions, flag.positions, flag.positions};
  for (Vec3& p : flag.positionSteps[1]) p.x += 0.3f;
  flag.positionSteps[1][2].z += 0.4f;  // one corner bends towards the camera
  for (Vec3& p : flag.positionSteps[2]) p += Vec3(0.5f, 0.2f, 0);
  addMeshInstance(s, addMesh(s, flag), Mat4());
  s.lights.push_back(pointLight({1, 3, 2}, Color(20.0f)));
  s.finalize();
  return s;
}

bool moves(const Scene& s, uint32_t primitive) {
  const Primitive& p = s.primitives[primitive];
  return !p.motion.empty() ||
         (p.kind == Primitive::Kind::kMesh && !s.meshes[p.mesh].positionSteps.empty());
}

class MovingHits : public testing::TestWithParam<const char*> {};

// Rays from a camera position at uniform random times: hit or miss, primitive and distance as
// Embree finds them. The two interpolate the same matrices (core/motion.h), each in its own
// float arithmetic: only rays grazing an edge may differ.
TEST_P(MovingHits, SameClosestHitsAndOcclusionAsEmbreeAtRandomTimes) {
  const Scene s = movingScene();
  auto embree = makeAccelerator("embree", s);
  auto other = makeAccelerator(GetParam(), s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int differ = 0, hits = 0, movingHits = 0;
  constexpr int kRays = 20000;
  for (int k = 0; k < kRays; ++k) {
    Ray r{{0, 0.8f, 3}, Vec3(2 * u(rng) - 1, 0.7f * u(rng) - 0.6f, -1)};
    r.time = u(rng);
    Hit a, b;
    const bool fa = embree->intersect(r, a), fb = other->intersect(r, b);
    if (fa != fb || (fa && (a.primitive != b.primitive || std::fabs(a.t - b.t) > 1e-4f * a.t))) {
      ++differ;
      continue;
    }
    if (!fa) continue;
    ++hits;
    movingHits += moves(s, a.primitive);
    // The surface point lies on the primitive where it was at the ray's time.
    const SurfacePoint sp = s.surface(r, a);
    EXPECT_NEAR(length(sp.p - (r.o + a.t * r.d)), 0.0f, 1e-4f);
    Ray shadow = r;
    shadow.tmax = a.t * 0.999f;
    shadow.o = r.o, shadow.d = r.d;
    EXPECT_FALSE(other->occluded(shadow));
    shadow.tmax = a.t * 1.001f;
    EXPECT_TRUE(other->occluded(shadow));
  }
  EXPECT_LE(differ, kRays / 1000) << "rays whose closest hit differs from Embree's";
  EXPECT_GT(movingHits, kRays / 20);  // the moving primitives were met
  EXPECT_GT(hits - movingHits, kRays / 10);
}

INSTANTIATE_TEST_SUITE_P(Accelerators, MovingHits, testing::Values("bvh", "bvh-gs", "naive"));

// Time moves the objects: the same ray at the shutter's open and close meets different ones.
TEST(MovingHits, TheRayTimePlacesTheObject) {
  const Scene s = movingScene();
  for (const char* name : {"embree", "bvh"}) {
    auto accel = makeAccelerator(name, s);
    Ray r{{0.4f, 0.35f, 3}, {0, 0, -1}};  // through the moving sphere's centre at open
    Hit h;
    r.time = 0;
    ASSERT_TRUE(accel->intersect(r, h)) << name;
    EXPECT_EQ(h.primitive, 1u) << name;
    EXPECT_NEAR(h.t, 3 - 0.35f, 1e-4f) << name;
    r.time = 1;  // the sphere has moved on to x = 1.2: the ray reaches the one behind, or none
    ASSERT_FALSE(accel->intersect(r, h) && h.primitive == 1u) << name;
    // The deforming quad: hit at open through its left part, gone from there at close.
    Ray q{{-0.2f, 1.0f, 3}, {0, 0, -1}};
    ASSERT_TRUE(accel->intersect(q, h)) << name;
    EXPECT_EQ(h.primitive, 4u) << name;
    EXPECT_NEAR(h.t, 3.8f, 1e-4f) << name;
    q.time = 1;
    EXPECT_FALSE(accel->intersect(q, h) && h.primitive == 4u) << name;
    // Halfway through the first segment: the quad moved 0.15 and its bent corner 0.2 nearer.
    q = Ray{{0.44f, 1.09f, 3}, {0, 0, -1}};
    q.time = 0.25f;
    ASSERT_TRUE(accel->intersect(q, h)) << name;
    EXPECT_EQ(h.primitive, 4u) << name;
    EXPECT_LT(h.t, 3.8f - 0.1f) << name;
    const SurfacePoint sp = s.surface(q, h);
    EXPECT_NEAR(sp.p.z, 3 - h.t, 1e-4f) << name;
  }
}

// The path tracer on both: pixel for pixel the same up to rays grazing an edge, so the
// images' means agree far within Monte Carlo noise.
TEST(MovingHits, PathTracedImagesAgreeBetweenEmbreeAndBvh) {
  const Scene s = movingScene();
  RenderSettings settings;
  settings.set("integrator", "path");
  settings.set("spp", 8);
  const CameraDesc cam = lookAt({0, 1.2f, 3}, {0, 0.4f, 0});
  constexpr int kW = 48, kH = 36;
  const Film a = renderFilm(s, cam, kW, kH, settings, nullptr, {}, "embree");
  const Film b = renderFilm(s, cam, kW, kH, settings, nullptr, {}, "bvh");
  double meanA = 0, meanB = 0, absDiff = 0;
  int same = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float* pa = a.pixel(Film::kBeauty, x, y);
      const float* pb = b.pixel(Film::kBeauty, x, y);
      for (int c = 0; c < 3; ++c) {
        meanA += pa[c], meanB += pb[c];
        absDiff += std::fabs(pa[c] - pb[c]);
      }
      same += std::fabs(pa[0] - pb[0]) < 1e-4f;
    }
  const double n = 3.0 * kW * kH;
  std::printf(
      "Embree vs bvh, moving scene: means %.5f / %.5f, mean |diff| %.2e, %d of %d pixels "
      "equal\n",
      meanA / n, meanB / n, absDiff / n, same, kW * kH);
  EXPECT_NEAR(meanA / n, meanB / n, 1e-3 * meanA / n);
  EXPECT_GT(same, kW * kH * 95 / 100);
}

}  // namespace
}  // namespace tray

// The in-house BVH's batched queries (accel/bvh_batch.cpp: packets of 8 and streams of 64 rays
// traversing together, and the loop) against its single-ray queries: the same closest hits, field
// by field, and the same occlusion, on incoherent and coherent rays over meshes, instances,
// analytic and unbounded shapes, motion blur and alpha-tested meshes.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "accel/bvh_accelerator.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "gltf/gltf_loader.h"
#include "tests/accel/batch_test_scenes.h"
#include "tests/scene_builder.h"
#include "tests/shapes/solid_meshes.h"

namespace tray {
namespace {

using namespace tray::test;

/// A random triangle soup placed three times (rotated and non-uniformly scaled), spheres, a box
/// and a plane under everything (unbounded: every ray tests it).
Scene instancedScene() {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Scene s;
  const int m = addMaterial(s, diffuse(Color(0.5f)));
  TriangleMesh mesh;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    const float size = 0.02f + 0.2f * u(rng) * u(rng);
    for (int k = 0; k < 3; ++k) {
      mesh.positions.push_back(c + size * Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
      mesh.indices.push_back(uint32_t(mesh.positions.size() - 1));
    }
  }
  mesh.material = m;
  const uint32_t soup = addMesh(s, std::move(mesh));
  addMeshInstance(s, soup, Mat4::identity());
  addMeshInstance(s, soup,
                  Mat4::translate({1.2f, 0.1f, 0.3f}) *
                      Mat4::rotate(0.2f, 0.3f, 0.1f, std::sqrt(1 - 0.14f)) *
                      Mat4::scale({1.0f, 0.7f, 1.3f}));
  addMeshInstance(s, soup, Mat4::translate({0.3f, 1.1f, -0.4f}) * Mat4::scale({0.5f, 0.5f, 0.5f}));
  for (int i = 0; i < 4; ++i) addSphere(s, {u(rng) * 2, u(rng), u(rng)}, 0.1f + 0.1f * u(rng), m);
  addShape(s, std::make_shared<Box>(Vec3(-0.1f), Vec3(0.1f)), Mat4::translate({1.0f, 1.2f, 0.5f}),
           m);
  addShape(s, std::make_shared<Plane>(), Mat4::translate({0, -0.2f, 0}), m);
  s.finalize();
  return s;
}

/// A cube instance turning and rising over three steps, a sphere moving over two, a quad whose
/// vertices move (a deforming mesh) and a static torus: motion of every kind.
Scene movingScene() {
  Scene s;
  const int m = addMaterial(s, diffuse(Color(0.6f)));
  addMovingCubeAndBall(s, m, m);
  addMeshInstance(s, addMesh(s, torusMesh(0.5f, 0.2f, 32, 16, m)), Mat4::translate({0, 0.3f, -1}));
  TriangleMesh flag;
  flag.positions = {
      {-0.3f, 0.9f, -0.8f}, {0.3f, 0.9f, -0.8f}, {0.3f, 1.1f, -0.8f}, {-0.3f, 1.1f, -0.8f}};
  flag.indices = {0, 1, 2, 0, 2, 3};
  flag.material = m;
  flag.positionSteps = {flag.positions, flag.positions};
  for (Vec3& p : flag.positionSteps[1]) p += Vec3(0.5f, 0.2f, 0.3f);
  addMeshInstance(s, addMesh(s, flag), Mat4());
  s.finalize();
  return s;
}

/// Every ray's batched answers against its single-ray ones. Ties: another primitive or triangle
/// at exactly the same t is as closest (coincident surfaces; the groups' traversal order differs
/// from a single ray's); at most 2% of the hits.
void expectSameAsSingleRays(const Accelerator& accel, const std::vector<Ray>& rays,
                            const std::string& what) {
  // Odd sizes leave part of the last group empty; short batches from the middle of the rays
  // (a coherent set's first rows may all miss).
  for (size_t n : {rays.size(), size_t(13), size_t(64 + 5)}) {
    const size_t first = (rays.size() - n) / 2;
    const std::span<const Ray> batch(rays.data() + first, n);
    std::vector<Hit> hits(batch.size());
    std::vector<uint8_t> found(batch.size()), blocked(batch.size());
    accel.intersectBatch(batch, hits, found);
    accel.occludedBatch(batch, blocked);
    size_t hitCount = 0, ties = 0, blockedCount = 0;
    for (size_t i = 0; i < batch.size(); ++i) {
      Hit h;
      const bool single = accel.intersect(batch[i], h);
      ASSERT_EQ(bool(found[i]), single) << what << " ray " << i;
      ASSERT_EQ(bool(blocked[i]), accel.occluded(batch[i])) << what << " ray " << i;
      blockedCount += blocked[i];
      if (!single) continue;
      ++hitCount;
      ASSERT_EQ(hits[i].t, h.t) << what << " ray " << i;
      if (hits[i].primitive != h.primitive || hits[i].triangle != h.triangle) {
        ++ties;
        continue;
      }
      EXPECT_EQ(hits[i].b1, h.b1) << what << " ray " << i;
      EXPECT_EQ(hits[i].b2, h.b2) << what << " ray " << i;
      EXPECT_EQ(hits[i].normal, h.normal) << what << " ray " << i;
      EXPECT_EQ(hits[i].uv.x, h.uv.x) << what << " ray " << i;
      EXPECT_EQ(hits[i].uv.y, h.uv.y) << what << " ray " << i;
      EXPECT_EQ(hits[i].material, h.material) << what << " ray " << i;
    }
    if (n == rays.size()) {
      EXPECT_GT(hitCount, n / 10) << what;  // the rays do meet the scene
      EXPECT_GT(n, blockedCount) << what;   // and not all are blocked
    }
    EXPECT_LE(ties, batch.size() / 50) << what;
  }
}

void expectEveryModeSameAsSingleRays(const Scene& scene, const std::string& name) {
  const std::vector<Ray> incoherent = randomRaysInBounds(scene, 3000, 11, true);
  const std::vector<Ray> coherent = coherentRays(scene, 48, 40);
  for (BvhBuilder builder : {BvhBuilder::kBinnedSah, BvhBuilder::kGoldsmithSalmon})
    for (BvhBatch batch : {BvhBatch::kLoop, BvhBatch::kPacket8, BvhBatch::kStream64}) {
      TwoLevelOptions options;
      options.build.builder = builder;
      options.batch = batch;
      const auto accel = makeTwoLevelAccelerator(scene, options);
      const std::string what = name + " " + builderName(builder) + " group " +
                               std::to_string(bvhBatchRays(batch));
      expectSameAsSingleRays(*accel, incoherent, what + " incoherent");
      expectSameAsSingleRays(*accel, coherent, what + " coherent");
    }
}

TEST(BvhBatch, InstancesAnalyticAndUnboundedShapes) {
  expectEveryModeSameAsSingleRays(instancedScene(), "instances");
}

TEST(BvhBatch, MotionBlur) {
  expectEveryModeSameAsSingleRays(movingScene(), "moving");
}

// The Cornell box; alpha-tested meshes (MASK and BLEND); TransmissionTest, whose coincident
// surfaces give ties at equal t.
TEST(BvhBatch, SharedScenes) {
  for (const char* file : {"/reference/cornell-box.gltf", "/gltf-features/AlphaBlendModeTest.glb",
                           "/gltf-samples/TransmissionTest.glb"})
    expectEveryModeSameAsSingleRays(loadGltf(std::string(TRAY_SHARED_DIR) + file), file);
}

// The registry's "bvh" (default options) traces batches in groups, not by the loop: what
// path_wavefront_test's SameAsScalar on "bvh" relies on to compare the groups' images with the
// single-ray path's.
TEST(BvhBatch, DefaultTracesGroups) {
  EXPECT_GT(bvhBatchRays(TwoLevelOptions{}.batch), 1);
}

}  // namespace
}  // namespace tray

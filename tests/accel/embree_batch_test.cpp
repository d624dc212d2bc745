// Accelerator::intersectBatch / occludedBatch against the single-ray queries they batch:
// every way of reaching Embree (loop, stream, 8-wide packets), the BVH's default batch, on
// opaque meshes and on alpha-tested ones (the filter finds each ray by its id in the batch),
// and the coherent batch the wavefront's camera rays take (on a pinhole's rays row by row).
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>

#include "accel/embree_accelerator.h"
#include "accel/registry.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "gltf/gltf_loader.h"
#include "tests/accel/batch_test_scenes.h"

namespace tray {
namespace {

/// intersectBatch (coherent: intersectCoherentBatch) and occludedBatch over `rays` give what
/// the single-ray queries give.
void expectSameAsSingleRays(const Accelerator& accel, const std::vector<Ray>& rays,
                            const std::string& what, bool coherent) {
  // Odd sizes leave part of the last packet empty (13: a full packet then a partial one over
  // it; 5: a batch's only packet, partial).
  for (size_t n : {rays.size(), size_t(13), size_t(5)}) {
    const std::span<const Ray> batch(rays.data(), n);
    // Slots holding another hit's fields: each found hit must be written whole.
    Hit stale;
    stale.normal = Vec3(1, 2, 3), stale.uv = {4, 5}, stale.material = 6;
    std::vector<Hit> hits(n, stale);
    std::vector<uint8_t> found(n), blocked(n);
    if (coherent)
      accel.intersectCoherentBatch(batch, hits, found);
    else
      accel.intersectBatch(batch, hits, found);
    accel.occludedBatch(batch, blocked);
    size_t hitCount = 0, ties = 0;
    for (size_t i = 0; i < n; ++i) {
      Hit h;
      const bool single = accel.intersect(rays[i], h);
      ASSERT_EQ(bool(found[i]), single) << what << " ray " << i;
      EXPECT_EQ(bool(blocked[i]), accel.occluded(rays[i])) << what << " ray " << i;
      if (!single) continue;
      ++hitCount;
      EXPECT_EQ(hits[i].t, h.t) << what << " ray " << i;
      // Coincident surfaces (the Cornell box's blocks stand on the floor, and these rays start
      // anywhere, inside blocks too): among hits at the same t, which one is reported depends
      // on traversal order, so another primitive at the same t is as closest.
      if (hits[i].primitive != h.primitive) {
        ++ties;
        continue;
      }
      EXPECT_EQ(hits[i].triangle, h.triangle) << what << " ray " << i;
      EXPECT_EQ(hits[i].b1, h.b1) << what << " ray " << i;
      EXPECT_EQ(hits[i].b2, h.b2) << what << " ray " << i;
      EXPECT_EQ(hits[i].material, h.material) << what << " ray " << i;
      EXPECT_EQ(hits[i].normal.x, h.normal.x) << what << " ray " << i;
      EXPECT_EQ(hits[i].uv.x, h.uv.x) << what << " ray " << i;
    }
    if (n == rays.size()) {
      EXPECT_GT(hitCount, n / 4) << what;  // the rays do meet the scene
    }
    EXPECT_LE(ties, n / 50) << what;
  }
}

TEST(EmbreeBatch, EveryModeEqualsSingleRayQueries) {
  for (const char* file :
       {"/reference/cornell-box.gltf", "/gltf-features/AlphaBlendModeTest.glb"}) {
    const Scene scene = loadGltf(std::string(TRAY_SHARED_DIR) + file);
    const std::vector<Ray> rays = test::randomRaysInBounds(scene, 2000, 7, false);
    const std::vector<Ray> camera = test::coherentRays(scene, 48, 40);
    for (EmbreeBatch mode : {EmbreeBatch::kLoop, EmbreeBatch::kStream, EmbreeBatch::kPacket8}) {
      const auto accel = makeEmbreeAccelerator(scene, mode);
      const std::string what = std::string(file) + " mode " + std::to_string(int(mode));
      expectSameAsSingleRays(*accel, rays, what, false);
      // The coherent traversal (the wavefront's camera rays) on rays that are not coherent,
      // and on rays that are.
      expectSameAsSingleRays(*accel, rays, what + " coherent", true);
      expectSameAsSingleRays(*accel, camera, what + " coherent camera", true);
    }
    const auto bvh = makeAccelerator("bvh", scene);
    expectSameAsSingleRays(*bvh, rays, std::string(file) + " bvh", false);
    expectSameAsSingleRays(*bvh, camera, std::string(file) + " bvh coherent camera", true);
  }
}

// Issue 40: Embree asserts RayK::valid() and aborts the process (exit 134) on a ray with a NaN
// or beyond-1.8e18 coordinate or a NaN t. Such a ray now meets nothing and, as a shadow ray,
// counts as occluded (it adds nothing), in every way of reaching Embree; a death test would
// catch the abort, so the queries run in this process: reaching the expectations is the test.
TEST(EmbreeBatch, RaysEmbreeRefusesMeetNothingInsteadOfAborting) {
  const Scene scene = loadGltf(std::string(TRAY_SHARED_DIR) + "/reference/cornell-box.gltf");
  std::vector<Ray> rays = test::randomRaysInBounds(scene, 16, 3, false);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  rays[1].o.x = nan;
  rays[3].d.y = 3e19f;
  rays[4].o.z = -2e19f;
  rays[6].tmax = nan;
  rays[9].tmin = nan;
  rays[12].d = Vec3(nan);
  const std::vector<size_t> refused = {1, 3, 4, 6, 9, 12};
  for (EmbreeBatch mode : {EmbreeBatch::kLoop, EmbreeBatch::kStream, EmbreeBatch::kPacket8}) {
    const auto accel = makeEmbreeAccelerator(scene, mode);
    std::vector<Hit> hits(rays.size());
    std::vector<uint8_t> found(rays.size()), blocked(rays.size());
    accel->intersectBatch(rays, hits, found);
    accel->occludedBatch(rays, blocked);
    for (size_t i : refused) {
      Hit h;
      EXPECT_FALSE(accel->intersect(rays[i], h)) << "ray " << i;
      EXPECT_TRUE(accel->occluded(rays[i])) << "ray " << i;
      EXPECT_FALSE(found[i]) << "mode " << int(mode) << " ray " << i;
      EXPECT_TRUE(blocked[i]) << "mode " << int(mode) << " ray " << i;
    }
    // The others are traced as before.
    for (size_t i = 0; i < rays.size(); ++i) {
      if (std::find(refused.begin(), refused.end(), i) != refused.end()) continue;
      Hit h;
      EXPECT_EQ(bool(found[i]), accel->intersect(rays[i], h)) << i;
    }
  }
}

}  // namespace
}  // namespace tray

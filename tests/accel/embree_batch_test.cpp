// Accelerator::intersectBatch / occludedBatch against the single-ray queries they batch:
// every way of reaching Embree (loop, stream, 8-wide packets), the BVH's default batch, on
// opaque meshes and on alpha-tested ones (the filter finds each ray by its id in the batch),
// and the coherent batch the wavefront's camera rays take (on a pinhole's rays row by row).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace tray

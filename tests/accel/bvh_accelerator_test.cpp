// The in-house accelerators ("bvh", "bvh-gs", "naive") against Embree: the same closest hits,
// occlusion and all-hits lists, on hand-made scenes and on random triangle soups.
#include "accel/bvh_accelerator.h"

#include <gtest/gtest.h>

#include <random>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

class BvhAccel : public ::testing::TestWithParam<std::string> {};

/// Two spheres on the z axis and one quad mesh instanced twice (at z = -6 and z = -8).
Scene lineOfObjects() {
  Scene s;
  int m = addMaterial(s, diffuse(Color(0.5f)));
  addSphere(s, {0, 0, -2}, 0.5f, m);
  addSphere(s, {0, 0, -4}, 0.5f, m);
  uint32_t quad = addMesh(s, quadMesh(1.0f, m));
  Mat4 faceZ = Mat4::rotate(std::sin(kPi / 4), 0, 0, std::cos(kPi / 4));
  addMeshInstance(s, quad, Mat4::translate({0, 0, -6}) * faceZ);
  addMeshInstance(s, quad, Mat4::translate({0, 0, -8}) * faceZ);
  s.finalize();
  return s;
}

TEST_P(BvhAccel, ClosestHitIsNearestPrimitiveAcrossLevels) {
  Scene s = lineOfObjects();
  auto accel = makeAccelerator(GetParam(), s);
  Hit h;
  ASSERT_TRUE(accel->intersect(Ray{{0, 0, 0}, {0, 0, -1}}, h));
  EXPECT_EQ(h.primitive, 0u);
  EXPECT_NEAR(h.t, 1.5f, 1e-5f);
  ASSERT_TRUE(accel->intersect(Ray{{0.5f, 0.5f, -7}, {0, 0, -1}}, h));
  EXPECT_EQ(h.primitive, 3u);  // the second instance of the shared mesh
  EXPECT_NEAR(h.t, 1.0f, 1e-5f);
  SurfacePoint sp = s.surface(Ray{{0.5f, 0.5f, -7}, {0, 0, -1}}, h);
  EXPECT_NEAR(sp.p.z, -8.0f, 1e-5f);
  EXPECT_NEAR(sp.p.x, 0.5f, 1e-5f);
}

TEST_P(BvhAccel, OcclusionRespectsRangeAndIgnoresStaleCache) {
  Scene s = lineOfObjects();
  auto accel = makeAccelerator(GetParam(), s);
  EXPECT_TRUE(accel->occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 2.0f}));  // caches sphere 0
  // The cached occluder lies beyond this range: the cache must not answer "occluded".
  EXPECT_FALSE(accel->occluded(Ray{{0, 0, 0}, {0, 0, -1}, 0.0f, 1.4f}));
  EXPECT_FALSE(accel->occluded(Ray{{0, 0, 0}, {0, 0, 1}}));
  EXPECT_TRUE(accel->occluded(Ray{{0.5f, 0.5f, -7}, {0, 0, -1}, 0.0f, 1.5f}));  // a triangle
  EXPECT_FALSE(accel->occluded(Ray{{0.5f, 0.5f, -7}, {0, 0, -1}, 0.0f, 0.9f}));
  // Another accelerator on this thread never reuses the first one's cache entry.
  Scene empty;
  empty.finalize();
  auto other = makeAccelerator(GetParam(), empty);
  EXPECT_FALSE(other->occluded(Ray{{0.5f, 0.5f, -7}, {0, 0, -1}, 0.0f, 1.5f}));
}

TEST_P(BvhAccel, AllHitsMatchEmbreeIncludingSphereExits) {
  Scene s = lineOfObjects();
  auto accel = makeAccelerator(GetParam(), s);
  auto embree = makeAccelerator("embree", s);
  std::vector<Hit> got, want;
  for (float tmax : {kInfinity, 3.0f, 6.5f}) {
    Ray r{{0.1f, 0.1f, 0}, {0, 0, -1}, 0.0f, tmax};
    accel->allHits(r, got);
    embree->allHits(r, want);
    ASSERT_EQ(got.size(), want.size()) << tmax;
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].primitive, want[i].primitive);
      EXPECT_NEAR(got[i].t, want[i].t, 1e-5f);
      EXPECT_EQ(got[i].material, want[i].material);
    }
  }
  accel->allHits(Ray{{0.1f, 0.1f, 0}, {0, 0, -1}}, got);
  EXPECT_EQ(got.size(), 6u);  // each sphere twice (enter, exit), each quad once
}

TEST_P(BvhAccel, InfinitePlaneIsHitFarAway) {
  Scene s;
  int m = addMaterial(s, diffuse(Color(0.5f)));
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), m);
  addSphere(s, {0, 5, 0}, 1.0f, m);
  s.finalize();
  auto accel = makeAccelerator(GetParam(), s);
  Hit h;
  ASSERT_TRUE(accel->intersect(Ray{{1e6f, 10, 0}, {0, -1, 0}}, h));
  EXPECT_FLOAT_EQ(h.t, 10.0f);
  ASSERT_TRUE(accel->intersect(Ray{{0, 10, 0}, {0, -1, 0}}, h));
  EXPECT_EQ(h.primitive, 1u);
  EXPECT_FALSE(accel->intersect(Ray{{0, 10, 0}, {1, 0, 0}}, h));
}

/// A random triangle soup (triangles of random size in a unit cube), placed by two instances
/// (one rotated and non-uniformly scaled), beside a few spheres and a box.
Scene randomSoup(uint32_t seed, int triangles) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Scene s;
  int m = addMaterial(s, diffuse(Color(0.5f)));
  TriangleMesh mesh;
  for (int i = 0; i < triangles; ++i) {
    Vec3 c{u(rng), u(rng), u(rng)};
    float size = 0.02f + 0.2f * u(rng) * u(rng);
    for (int k = 0; k < 3; ++k) {
      mesh.positions.push_back(c + size * Vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
      mesh.indices.push_back(uint32_t(mesh.positions.size() - 1));
    }
  }
  mesh.material = m;
  uint32_t id = addMesh(s, std::move(mesh));
  addMeshInstance(s, id, Mat4::identity());
  addMeshInstance(s, id,
                  Mat4::translate({1.2f, 0.1f, 0.3f}) *
                      Mat4::rotate(0.2f, 0.3f, 0.1f, std::sqrt(1 - 0.14f)) *
                      Mat4::scale({1.0f, 0.7f, 1.3f}));
  for (int i = 0; i < 4; ++i) addSphere(s, {u(rng) * 2, u(rng), u(rng)}, 0.1f + 0.1f * u(rng), m);
  addShape(s, std::make_shared<Box>(Vec3(-0.1f), Vec3(0.1f)), Mat4::translate({1.0f, 1.2f, 0.5f}),
           m);
  s.finalize();
  return s;
}

struct Mismatches {
  int hitMiss = 0, primitive = 0, t = 0, barycentric = 0, occluded = 0;
};

TEST_P(BvhAccel, RandomRaysAgainstRandomSoupsMatchEmbree) {
  // 100k rays for the trees; the naive accelerator tests every triangle, so fewer.
  const int soups = 10, raysPerSoup = GetParam() == "naive" ? 1000 : 10000;
  Mismatches bad;
  int hits = 0;
  float maxPointError = 0;
  for (int k = 0; k < soups; ++k) {
    Scene s = randomSoup(1000u + k, 2000);
    auto accel = makeAccelerator(GetParam(), s);
    auto embree = makeAccelerator("embree", s);
    std::mt19937 rng(77u + k);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < raysPerSoup; ++i) {
      Vec3 o{3 * u(rng) - 0.5f, 3 * u(rng) - 1.0f, 3 * u(rng) - 1.0f};
      Vec3 target{2.2f * u(rng), 1.4f * u(rng), 1.4f * u(rng)};
      Ray r{o, (target - o) * (0.5f + u(rng)), 0.0f, kInfinity};
      if (i % 4 == 0) r.tmax = u(rng) * 1.5f;  // bounded rays too
      Hit a, b;
      bool ha = accel->intersect(r, a), hb = embree->intersect(r, b);
      if (ha != hb) {
        ++bad.hitMiss;
        continue;
      }
      bad.occluded += accel->occluded(r) != ha;
      if (!ha) continue;
      ++hits;
      if (a.primitive != b.primitive || a.triangle != b.triangle) {
        ++bad.primitive;
        continue;
      }
      bad.t += std::fabs(a.t - b.t) > 1e-5f * std::max(1.0f, b.t);
      // Barycentrics are ill-conditioned for grazing rays and slivers, so compare the surface
      // points they give (world units; the soups span about 2.5).
      float dp = length(s.surface(r, a).p - s.surface(r, b).p);
      maxPointError = std::max(maxPointError, dp);
      bad.barycentric += dp > 2e-5f;
    }
  }
  std::printf("%d rays, %d hits; largest distance between the two hit points %g\n",
              soups * raysPerSoup, hits, maxPointError);
  EXPECT_GT(hits, soups * raysPerSoup / 4);  // the rays do hit things
  EXPECT_EQ(bad.hitMiss, 0);
  EXPECT_EQ(bad.primitive, 0);
  EXPECT_EQ(bad.t, 0);
  EXPECT_EQ(bad.barycentric, 0);
  EXPECT_EQ(bad.occluded, 0);
}

TEST_P(BvhAccel, AllHitsOnRandomSoupsMatchEmbree) {
  Scene s = randomSoup(4242u, 1000);
  auto accel = makeAccelerator(GetParam(), s);
  auto embree = makeAccelerator("embree", s);
  std::mt19937 rng(5u);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Hit> got, want;
  size_t total = 0;
  for (int i = 0; i < 500; ++i) {
    Vec3 o{3 * u(rng) - 0.5f, 3 * u(rng) - 1.0f, -1.0f};
    Vec3 target{2.2f * u(rng), 1.4f * u(rng), 1.4f * u(rng)};
    Ray r{o, target - o, 0.0f, kInfinity};
    accel->allHits(r, got);
    embree->allHits(r, want);
    ASSERT_EQ(got.size(), want.size()) << i;
    for (size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].primitive, want[k].primitive);
      EXPECT_EQ(got[k].triangle, want[k].triangle);
      EXPECT_NEAR(got[k].t, want[k].t, 1e-5f * std::max(1.0f, want[k].t));
    }
    total += got.size();
  }
  EXPECT_GT(total, 200u);
}

INSTANTIATE_TEST_SUITE_P(Accelerators, BvhAccel, ::testing::Values("bvh", "bvh-gs", "naive"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (c == '-') c = '_';
                           return n;
                         });

TEST(BvhQuality, BothBuildersReportTheirSahCost) {
  Scene s = randomSoup(9u, 5000);
  auto sah = makeAccelerator("bvh", s);
  auto gs = makeAccelerator("bvh-gs", s);
  BvhQuality qs = bvhQuality(*sah), qg = bvhQuality(*gs);
  EXPECT_GT(qs.meshSahCost, 1.0);
  EXPECT_GT(qg.meshSahCost, 1.0);
  EXPECT_GT(qs.nodes, 0u);
  EXPECT_EQ(bvhQuality(*makeAccelerator("embree", s)).nodes, 0u);
}

}  // namespace
}  // namespace tray

// Embree places a static mesh used once in world space instead of as an instance
// (accel/embree_accelerator.cpp, flattens): its hits must be the instanced tree's hits, as the
// in-house BVH (always two levels) finds them, for closest hits, occlusion, the alpha test and
// all-hits queries.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "accel/embree_accelerator.h"
#include "accel/registry.h"
#include "tests/scene_builder.h"
#include "textures/alpha.h"

namespace tray {
namespace {

using namespace tray::test;

/// An n x n grid of quads over [-1, 1]^2 in the y = 0 plane (2 n^2 triangles), u = x, v = z
/// mapped to [0, 1]; vertex alpha 1 on x < 0 and 0 on x > 0 (the middle column ramps).
TriangleMesh grid(int n, int material) {
  TriangleMesh m;
  m.material = material;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -1 + 2.0f * i / n, z = -1 + 2.0f * j / n;
      m.positions.push_back({x, 0, z});
      m.uvs.push_back({(x + 1) / 2, (z + 1) / 2});
      m.colors.push_back(Color(1.0f));
      m.colorAlphas.push_back(x < 0 ? 1.0f : x > 0 ? 0.0f : 0.5f);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
    }
  return m;
}

/// A rotated, scaled, moved grid of 1152 triangles placed once (flattened), the same triangles
/// as a second mesh placed twice (instanced), and a sphere (user geometry) between them.
Scene scene(const Material& material) {
  Scene s;
  const int mat = addMaterial(s, material);
  const float q = 1 / std::sqrt(0.99f);  // a unit quaternion
  const Mat4 turn = Mat4::rotate(0.3f * q, 0.5f * q, 0.1f * q, 0.8f * q);
  addMeshInstance(s, addMesh(s, grid(24, mat)),
                  Mat4::translate({0.3f, -0.2f, 0.1f}) * turn * Mat4::scale({2, 1, 1.5f}));
  const uint32_t shared = addMesh(s, grid(24, mat));
  addMeshInstance(s, shared, Mat4::translate({0, 2, 0}));
  addMeshInstance(s, shared, Mat4::translate({0, -2, 0}) * turn);
  addSphere(s, {0.5f, 1.0f, 0.2f}, 0.4f, mat);
  s.finalize();
  return s;
}

/// Random rays from a box around the scene toward random points inside it.
std::vector<Ray> rays(int count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> outer(-4, 4), inner(-1.5f, 1.5f);
  std::vector<Ray> out;
  for (int k = 0; k < count; ++k) {
    const Vec3 o{outer(rng), outer(rng), outer(rng)}, to{inner(rng), inner(rng), inner(rng)};
    out.push_back(Ray{o, to - o});
  }
  return out;
}

void expectSameHit(const Scene& s, const Ray& r, const Hit& e, const Hit& b) {
  ASSERT_EQ(e.primitive, b.primitive);
  EXPECT_NEAR(e.t, b.t, 1e-6f + 1e-5f * b.t);  // t in units of |d| (up to ~8)
  if (s.primitives[e.primitive].kind != Primitive::Kind::kMesh) return;
  EXPECT_EQ(e.triangle, b.triangle);
  // Barycentrics from world- instead of object-space vertices: the same point up to rounding.
  EXPECT_NEAR(e.b1, b.b1, 2e-4f);
  EXPECT_NEAR(e.b2, b.b2, 2e-4f);
  const SurfacePoint pe = s.surface(r, e), pb = s.surface(r, b);
  EXPECT_LT(length(pe.p - pb.p), 1e-4f);
}

/// Closest hits and occlusion of random rays on Embree and the BVH compared; `visit` sees each
/// of Embree's hits.
template <class Visit>
void forEachHit(const Scene& s, Visit visit) {
  auto embree = makeAccelerator("embree", s), bvh = makeAccelerator("bvh", s);
  for (const Ray& r : rays(20000)) {
    Hit e, b;
    const bool he = embree->intersect(r, e), hb = bvh->intersect(r, b);
    ASSERT_EQ(he, hb);
    EXPECT_EQ(embree->occluded(r), bvh->occluded(r));
    if (!he) continue;
    expectSameHit(s, r, e, b);
    visit(e);
  }
}

TEST(EmbreeFlatten, OnlyStaticMeshesPlacedOnce) {
  Scene s = scene(diffuse(Color(0.5f)));
  EXPECT_EQ(embreeFlattenedMeshes(s), (std::vector<uint8_t>{1, 0, 0, 0}));
  // However small (two triangles; before 2026-12-03 only meshes of 1024 triangles and more),
  // but not a mesh without triangles (nothing to attach).
  Scene small;
  const int mat = addMaterial(small, diffuse(Color(0.5f)));
  addMeshInstance(small, addMesh(small, grid(1, mat)), Mat4::translate({0, 1, 0}));
  TriangleMesh empty;
  empty.material = mat;
  addMeshInstance(small, addMesh(small, empty), Mat4::translate({0, 2, 0}));
  small.finalize();
  EXPECT_EQ(embreeFlattenedMeshes(small), (std::vector<uint8_t>{1, 0}));
  s.primitives[0].motion = {s.primitives[0].toWorld.m, s.primitives[0].toWorld.m};  // moving
  EXPECT_EQ(embreeFlattenedMeshes(s), (std::vector<uint8_t>{0, 0, 0, 0}));
}

TEST(EmbreeFlatten, TwoLevelsUnlessABigMeshIsFlattened) {
  // The grid of 1152 triangles placed once: one tree. Small meshes placed once, however many
  // triangles in all, and a big shared grid (instanced): two levels.
  Scene big = scene(diffuse(Color(0.5f)));
  EXPECT_FALSE(embreeTwoLevelTop(big, embreeFlattenedMeshes(big)));
  Scene small;
  const int mat = addMaterial(small, diffuse(Color(0.5f)));
  addMeshInstance(small, addMesh(small, grid(1, mat)), Mat4::translate({0, 1, 0}));
  addMeshInstance(small, addMesh(small, grid(1, mat)), Mat4::translate({0, 2, 0}));
  for (int k = 0; k < 5; ++k)  // 5 x 288 triangles
    addMeshInstance(small, addMesh(small, grid(12, mat)), Mat4::translate({0, -1.0f - k, 0}));
  const uint32_t shared = addMesh(small, grid(24, mat));
  addMeshInstance(small, shared, Mat4::translate({0, 3, 0}));
  addMeshInstance(small, shared, Mat4::translate({0, 4, 0}));
  small.finalize();
  EXPECT_EQ(embreeFlattenedMeshes(small), (std::vector<uint8_t>{1, 1, 1, 1, 1, 1, 1, 0, 0}));
  EXPECT_TRUE(embreeTwoLevelTop(small, embreeFlattenedMeshes(small)));
  // Either way the hits are the BVH's.
  auto embree = makeAccelerator("embree", small), bvh = makeAccelerator("bvh", small);
  int hits = 0;
  for (const Ray& r : rays(4000)) {
    Hit e, b;
    const bool he = embree->intersect(r, e), hb = bvh->intersect(r, b);
    ASSERT_EQ(he, hb);
    EXPECT_EQ(embree->occluded(r), bvh->occluded(r));
    if (he) expectSameHit(small, r, e, b), ++hits;
  }
  EXPECT_GT(hits, 500);
}

TEST(EmbreeFlatten, OneTreeOverManyInstances) {
  // kEmbreeTwoLevelMaxPrimitives placements of one small mesh (EXT_mesh_gpu_instancing): one
  // tree, whose hits are still the BVH's.
  Scene s;
  const int mat = addMaterial(s, diffuse(Color(0.5f)));
  const uint32_t shared = addMesh(s, grid(1, mat));
  for (size_t k = 0; k + 1 < kEmbreeTwoLevelMaxPrimitives; ++k)
    addMeshInstance(s, shared,
                    Mat4::translate({float(k % 100) * 0.05f - 2.5f, float(k / 100) * 0.05f - 2.5f,
                                     -0.01f * float(k % 7)}) *
                        Mat4::scale({0.02f, 0.02f, 0.02f}));  // 0.04 wide: no overlaps
  s.finalize();
  EXPECT_TRUE(embreeTwoLevelTop(s, embreeFlattenedMeshes(s)));
  addMeshInstance(s, shared, Mat4::translate({0, 0, 5}));
  EXPECT_FALSE(embreeTwoLevelTop(s, embreeFlattenedMeshes(s)));
  auto embree = makeAccelerator("embree", s), bvh = makeAccelerator("bvh", s);
  int hits = 0;
  for (const Ray& r : rays(2000)) {
    Hit e, b;
    const bool he = embree->intersect(r, e), hb = bvh->intersect(r, b);
    ASSERT_EQ(he, hb);
    if (he) expectSameHit(s, r, e, b), ++hits;
  }
  EXPECT_GT(hits, 100);
}

TEST(EmbreeFlatten, BigMeshPlacedOnceHitsAsTheInstancedTree) {
  Scene s = scene(diffuse(Color(0.5f)));
  int meshHits[3] = {0, 0, 0};
  forEachHit(s, [&](const Hit& e) {
    if (e.primitive < 3) ++meshHits[e.primitive];
  });
  // Each placement is met often: the flattened grid, and both instances of the shared one.
  for (int n : meshHits) EXPECT_GT(n, 500);
}

TEST(EmbreeFlatten, BatchesAndAllHitsAgree) {
  Scene s = scene(diffuse(Color(0.5f)));
  auto embree = makeAccelerator("embree", s), bvh = makeAccelerator("bvh", s);
  const std::vector<Ray> rs = rays(4096);
  std::vector<Hit> eh(rs.size()), bh(rs.size());
  std::vector<uint8_t> ef(rs.size()), bf(rs.size());
  embree->intersectBatch(rs, eh, ef);
  bvh->intersectBatch(rs, bh, bf);
  for (size_t k = 0; k < rs.size(); ++k) {
    ASSERT_EQ(ef[k], bf[k]);
    if (ef[k]) expectSameHit(s, rs[k], eh[k], bh[k]);
  }
  std::vector<Hit> ea, ba;
  int crossings = 0;
  for (size_t k = 0; k < 500; ++k) {
    embree->allHits(rs[k], ea);
    bvh->allHits(rs[k], ba);
    ASSERT_EQ(ea.size(), ba.size());
    for (size_t i = 0; i < ea.size(); ++i) expectSameHit(s, rs[k], ea[i], ba[i]);
    crossings += int(ea.size());
  }
  EXPECT_GT(crossings, 200);
}

TEST(EmbreeFlatten, AlphaTestAppliesToTheFlattenedMesh) {
  Material m;
  m.alphaMode = AlphaMode::kMask;  // vertex alpha: the x < 0 half is solid, x > 0 cut out
  Scene s = scene(m);
  int flatHits = 0;
  forEachHit(s, [&](const Hit& e) {
    if (e.primitive != 0) return;
    ++flatHits;
    EXPECT_GE(vertexAlpha(s.meshes[0], e.triangle, e.b1, e.b2), 0.5f);  // never the cut half
  });
  EXPECT_GT(flatHits, 200);
}

}  // namespace
}  // namespace tray

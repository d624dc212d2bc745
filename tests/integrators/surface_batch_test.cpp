// The SIMD surface points of integrators/surface_batch.h against Scene::surface, bit for bit, on
// every SIMD target the CPU has: random placements, meshes with and without normals and uvs,
// degenerate normals, material overrides, hits spread over many primitives, and the
// primitives the kernel leaves to the scalar code.
#include "integrators/surface_batch.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "shapes/sphere.h"
#include "tests/scene_builder.h"
#include "tests/simd_targets.h"

namespace tray {
namespace {

using test::randomPlacement;

/// Mesh `k` of a random scene: every fourth without normals, every third without uvs; some
/// vertex normals zero or NaN (the flat fallback) or facing away (ng flips).
TriangleMesh randomMesh(std::mt19937_64& rng, int k) {
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  TriangleMesh m;
  const int vertices = std::uniform_int_distribution<int>(3, 40)(rng);
  for (int v = 0; v < vertices; ++v) {
    m.positions.push_back({u(rng), u(rng), u(rng)});
    if (k % 4 != 0) {
      const int kind = std::uniform_int_distribution<int>(0, 9)(rng);
      const float nan = std::numeric_limits<float>::quiet_NaN();
      m.normals.push_back(kind == 0   ? Vec3(0.0f)
                          : kind == 1 ? Vec3(nan, 0.0f, 1.0f)
                                      : Vec3(u(rng), u(rng), u(rng)));
    }
    if (k % 3 != 0) m.uvs.push_back({u(rng), u(rng)});
  }
  const int triangles = std::uniform_int_distribution<int>(1, 30)(rng);
  for (int t = 0; t < 3 * triangles; ++t)
    m.indices.push_back(uint32_t(std::uniform_int_distribution<int>(0, vertices - 1)(rng)));
  m.material = k % 2;
  return m;
}

void expectSameBits(float a, float b, const char* what, size_t j) {
  EXPECT_EQ(std::bit_cast<uint32_t>(a), std::bit_cast<uint32_t>(b))
      << what << " of hit " << j << ": " << a << " vs " << b;
}

void expectSame(const SurfacePoint& got, const SurfacePoint& want, size_t j) {
  for (int a = 0; a < 3; ++a) {
    expectSameBits(got.p[a], want.p[a], "p", j);
    expectSameBits(got.ng[a], want.ng[a], "ng", j);
    expectSameBits(got.n[a], want.n[a], "n", j);
    expectSameBits(got.front[a], want.front[a], "front", j);
  }
  expectSameBits(got.uv.x, want.uv.x, "uv.x", j);
  expectSameBits(got.uv.y, want.uv.y, "uv.y", j);
  EXPECT_EQ(got.material, want.material) << j;
  EXPECT_EQ(got.primitive, want.primitive) << j;
  EXPECT_EQ(got.frontFace, want.frontFace) << j;
  expectSameBits(got.time, want.time, "time", j);
}

/// A scene of random meshes (and a sphere, and a moving mesh: the scalar code's), and a wave
/// of random hits on it; returns the hits compared.
int compareRandomWaves(std::mt19937_64& rng) {
  Scene scene;
  scene.materials.resize(3);
  const int meshes = std::uniform_int_distribution<int>(1, 12)(rng);
  for (int k = 0; k < meshes; ++k) {
    scene.meshes.push_back(randomMesh(rng, k));
    Primitive p;
    p.mesh = uint32_t(k);
    p.toWorld = randomPlacement(rng);
    if (k == 5) p.motion = {p.toWorld.m, randomPlacement(rng).m};  // left to Scene::surface
    scene.primitives.push_back(p);
  }
  Primitive sphere;
  sphere.kind = Primitive::Kind::kShape;
  sphere.shape = std::make_shared<Sphere>(1.0f);
  sphere.toWorld = randomPlacement(rng);
  scene.primitives.push_back(sphere);
  scene.finalize();
  const SurfaceBatch batch(scene);
  EXPECT_TRUE(batch.useful());
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), unit(0.0f, 1.0f);
  const size_t n = std::uniform_int_distribution<size_t>(1, 300)(rng);
  std::vector<Ray> rays(n);
  std::vector<Hit> hits(n);
  std::vector<uint8_t> found(n);
  for (size_t j = 0; j < n; ++j) {
    rays[j].o = {u(rng), u(rng), u(rng)};
    rays[j].d = {u(rng), u(rng), u(rng)};
    rays[j].time = unit(rng);
    found[j] = j % 7 != 3;
    Hit& h = hits[j];
    h.primitive = uint32_t(std::uniform_int_distribution<int>(0, meshes)(rng));
    h.t = unit(rng);
    h.material = j % 11 == 0 ? 2 : -1;  // a CSG override
    if (h.primitive < uint32_t(meshes)) {
      const auto triangles = int(scene.meshes[h.primitive].indices.size() / 3);
      h.triangle = uint32_t(std::uniform_int_distribution<int>(0, triangles - 1)(rng));
      h.b1 = unit(rng), h.b2 = unit(rng) * (1.0f - h.b1);
    } else {
      const Vec3 d = normalize(Vec3(u(rng), u(rng), u(rng)));
      h.normal = d;
      h.uv = {unit(rng), unit(rng)};
      rays[j].o = sphere.toWorld.point(2.0f * d);
      rays[j].d = sphere.toWorld.vector(-d);
      h.t = 1.0f;
    }
  }
  std::vector<SurfacePoint> out(n);
  SurfaceBatch::Scratch scratch;
  batch.compute(rays, hits, found, out, scratch);
  int compared = 0;
  for (size_t j = 0; j < n; ++j) {
    if (!found[j]) {
      EXPECT_EQ(out[j].primitive, kNoPrimitive) << "hit " << j << " was not found: left as is";
      continue;
    }
    expectSame(out[j], scene.surface(rays[j], hits[j]), j);
    ++compared;
  }
  // The scratch is ready for the next call: counts back to zero.
  for (uint32_t c : scratch.count) EXPECT_EQ(c, 0u);
  return compared;
}

TEST(SurfaceBatch, SameBitsAsSceneSurface) {
  test::onEverySimdTarget(20000, [] {
    std::mt19937_64 rng(20261203);
    int compared = 0;
    for (int trial = 0; trial < 200 && !testing::Test::HasFailure(); ++trial)
      compared += compareRandomWaves(rng);
    return compared;
  });
}

TEST(SurfaceBatch, ScenesWithoutStaticMeshesAreLeftToTheScalarCode) {
  Scene shapes;
  Primitive sphere;
  sphere.kind = Primitive::Kind::kShape;
  sphere.shape = std::make_shared<Sphere>(1.0f);
  shapes.primitives.push_back(sphere);
  shapes.finalize();
  EXPECT_FALSE(SurfaceBatch(shapes).useful());

  Scene deforming;  // morph targets: positions per time step
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.indices = {0, 1, 2};
  m.positionSteps = {m.positions, m.positions};
  deforming.meshes.push_back(m);
  deforming.primitives.push_back(Primitive{});
  deforming.finalize();
  EXPECT_FALSE(SurfaceBatch(deforming).useful());
  deforming.meshes[0].positionSteps.clear();
  EXPECT_TRUE(SurfaceBatch(deforming).useful());
}

}  // namespace
}  // namespace tray

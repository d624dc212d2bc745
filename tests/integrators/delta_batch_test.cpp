// The SIMD delta stage (integrators/delta_batch.h) on every SIMD target the CPU has:
// - its kernel against the scalar pieces PathEstimator::step runs for smooth glass (Bsdf::
//   sample, its lone lobe's pdf check, the throughput and spawnRay), bit for bit, on random
//   vertices: wo above and below n, grazing and near the normal, relative IORs above and
//   below 1 (total internal reflection included) and index-matched, tinted glass, both lobes
//   (a sample of probability 0 is compared too, though smooth glass has none in practice);
// - whole renders of random scenes with nested, tinted and absorbing glass through `path`
//   (the wavefront, which defers its smooth glass vertices to the stage) against
//   `path-scalar`, bit for bit.
#include "integrators/delta_batch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/ray.h"
#include "core/simd_lanes.h"
#include "materials/bsdf.h"
#include "materials/fresnel.h"
#include "tests/integrators/shading_stage_test.h"
#include "tests/scene_builder.h"
#include "tests/simd_targets.h"

namespace tray {
namespace {

using test::expectSameBits;
using test::randomUnit;

/// Smooth glass of tint `tint`, as step() evaluates it.
ShadingMaterial glassOf(const Color& tint, const Vec3& n) {
  Material m = test::diffuse(tint);
  m.metallic = 0, m.roughness = 0, m.transmission = 1;
  return ShadingMaterial::of(m, n);
}

/// One random smooth glass vertex in entry q of `m`.
void randomVertex(std::mt19937_64& rng, ShadingLanes& m, size_t q) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), u(-3.0f, 3.0f);
  m.p[q] = {u(rng), u(rng), u(rng)};
  m.ng[q] = randomUnit(rng);
  m.n[q] = q % 5 == 0 ? -m.ng[q] : randomUnit(rng);
  m.wo[q] = randomUnit(rng);                                               // above or below n
  if (q % 10 == 3) m.wo[q] = normalize(m.n[q] + 0.05f * randomUnit(rng));  // near the normal
  if (q % 10 == 7) m.wo[q] = normalize(cross(m.n[q], randomUnit(rng)));    // grazing
  m.albedo[q] = q % 3 == 0 ? Color(1.0f) : Color(u01(rng), u01(rng), u01(rng));
  m.beta[q] = {u01(rng) * 3, u01(rng), u01(rng)};
  m.lobeDraw[q] = q % 11 == 0 ? 0.0f : u01(rng);
  const float eta[] = {1.5f, 1.0f / 1.5f, 1.0f + 2.0f * u01(rng), 1.0f, 1.33f / 1.5f};
  m.eta[q] = eta[q % 5];
}

/// What the comparisons met, so that the test can tell it compared each case.
struct Met {
  int vertices = 0, reflected = 0, refracted = 0, totalInternal = 0, invalid = 0;
};

/// Entry q's outputs against the scalar pieces step() runs.
void compareVertex(const ShadingLanes& m, size_t q, Met& met) {
  const ShadingMaterial sm = glassOf(m.albedo[q], m.n[q]);
  ASSERT_TRUE(Bsdf::isSmoothGlass(sm));
  const Bsdf bsdf(sm, m.n[q], m.eta[q]);
  ASSERT_FALSE(bsdf.hasNonDelta());
  const BsdfSample bs = bsdf.sample(m.wo[q], m.lobeDraw[q], {0.5f, 0.5f});
  expectSameBits(m.pdf[q], bs.pdf, "pdf", q);
  ++met.vertices;
  if (!(bs.pdf > 0)) {
    ++met.invalid;
    return;
  }
  EXPECT_TRUE(bs.delta) << q;
  EXPECT_EQ(bool(m.transmitted[q]), bs.transmission) << q;
  expectSameBits(m.etaScale[q], bs.etaScale, "etaScale", q);
  ++(bs.transmission ? met.refracted : met.reflected);
  // Leaving a denser medium beyond the critical angle: Fresnel 1, always reflected.
  float etap;
  Vec3 wt;
  const Vec3 woLocal = bsdf.frame().toLocal(m.wo[q]);
  if (!refractDirection(woLocal, Vec3(0, 0, 1), m.eta[q], etap, wt)) ++met.totalInternal;
  const Color beta = m.beta[q] * (bs.f * (std::fabs(dot(bs.wi, m.n[q])) / bs.pdf));
  expectSameBits(m.nextBeta[q], beta, "throughput", q);
  const Ray next = spawnRay(m.p[q], m.ng[q], bs.wi, 0.0f);
  expectSameBits(m.rayOrigin[q], next.o, "ray origin", q);
  expectSameBits(m.rayDir[q], next.d, "ray direction", q);
}

TEST(DeltaBatch, KernelIsTheScalarStepBitForBit) {
  const DeltaBatch batch;
  if (!hasSimdTarget()) GTEST_SKIP() << "no SIMD target: the wavefront keeps to scalar code";
  ASSERT_TRUE(batch.useful());
  std::mt19937_64 rng(23);
  test::onEverySimdTarget(1000, [&] {
    Met met;
    ShadingLanes m;
    for (int wave = 0; wave < 40 && !testing::Test::HasFailure(); ++wave) {
      const size_t count = std::uniform_int_distribution<size_t>(1, 100)(rng);  // partial vectors
      m.reset(count);
      for (m.count = 0; m.count < count; ++m.count) randomVertex(rng, m, m.count);
      batch.compute(m);
      for (size_t q = 0; q < count; ++q) compareVertex(m, q, met);
    }
    // Every case was compared, not only skipped.
    EXPECT_GT(met.reflected, met.vertices / 20);
    EXPECT_GT(met.refracted, met.vertices / 4);
    EXPECT_GT(met.totalInternal, met.vertices / 50);
    return met.vertices;
  });
}

TEST(DeltaBatch, TakesSmoothGlassOnly) {
  ShadingMaterial sm = glassOf(Color(0.9f, 1.0f, 0.8f), Vec3(0, 0, 1));
  EXPECT_TRUE(Bsdf::isSmoothGlass(sm));
  sm.roughness = 0.01f;  // alpha 1e-4: still two delta lobes
  EXPECT_TRUE(Bsdf::isSmoothGlass(sm));
  for (const auto& change : std::vector<void (*)(ShadingMaterial&)>{
           [](ShadingMaterial& s) { s.roughness = 0.3f; },     // rough glass: GGX lobes
           [](ShadingMaterial& s) { s.transmission = 0.5f; },  // glass over plastic
           [](ShadingMaterial& s) { s.metallic = 0.2f; },
           [](ShadingMaterial& s) { s.clearcoat = 0.5f; },
           [](ShadingMaterial& s) { s.sheenColor = Color(0.2f); },
           [](ShadingMaterial& s) { s.transmission = std::nanf(""); },
           [](ShadingMaterial& s) { s.roughness = std::nanf(""); }}) {
    ShadingMaterial other = sm;
    change(other);
    EXPECT_FALSE(Bsdf::isSmoothGlass(other));
  }
  ShadingMaterial matte = ShadingMaterial::of(test::diffuse(Color(0.5f)), Vec3(0, 0, 1));
  EXPECT_FALSE(Bsdf::isSmoothGlass(matte));
}

/// Glass spheres (tinted, nested with priorities, absorbing in some scenes) over matte and
/// glossy triangles, under an emissive triangle and a sky.
Scene randomScene(std::mt19937_64& rng, int index) {
  Scene scene;
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  Material light = test::diffuse(Color(0.0f));
  light.emissive = Color(8.0f, 7.0f, 6.0f);
  light.doubleSided = true;
  test::addMeshInstance(scene,
                        test::addMesh(scene, test::quadMesh(1.0f, test::addMaterial(scene, light))),
                        Mat4::translate({0, 4, 0}));
  scene.environment.background = {0.3f, 0.5f, 0.8f};
  for (int k = 0; k < 6; ++k) {
    Material m = test::diffuse(Color(u01(rng), u01(rng), u01(rng)));
    m.roughness = k % 2 == 0 ? 1.0f : 0.2f + 0.5f * u01(rng);
    test::addMeshInstance(
        scene, test::addMesh(scene, test::randomTriangle(rng, test::addMaterial(scene, m))),
        Mat4::translate({0, 0, -2}));
  }
  Material floorMaterial = test::diffuse(Color(0.7f));
  test::addMeshInstance(
      scene, test::addMesh(scene, test::quadMesh(4.0f, test::addMaterial(scene, floorMaterial))),
      Mat4::translate({0, -1.5f, 0}));
  Material glass = test::diffuse(index % 2 == 0 ? Color(1.0f) : Color(0.9f, 0.7f, 1.0f));
  glass.transmission = 1.0f, glass.roughness = 0.0f, glass.ior = 1.5f, glass.priority = 1;
  if (index % 3 == 2) glass.layers.attenuationColor = {0.8f, 0.5f, 0.3f};
  if (index % 3 == 2) glass.layers.attenuationDistance = 1.0f;
  test::addSphere(scene, {0, 0, 1}, 1.0f, test::addMaterial(scene, glass));
  if (index % 2 == 1) {  // water inside, a real interface (a higher priority)
    Material water = glass;
    water.ior = 1.33f, water.priority = 2, water.baseColor = Color(1.0f);
    test::addSphere(scene, {0.2f, 0, 1.2f}, 0.5f, test::addMaterial(scene, water));
  }
  scene.cameras.push_back(test::lookAt({0.0f, 0.5f, 5.0f}, {0, 0, 0}));
  return scene;
}

TEST(DeltaBatch, RandomScenesRenderAsTheScalarPathTracer) {
  if (!hasSimdTarget()) GTEST_SKIP() << "no SIMD target: the wavefront keeps to scalar code";
  test::randomScenesOnEveryTarget(29, randomScene);
}

}  // namespace
}  // namespace tray

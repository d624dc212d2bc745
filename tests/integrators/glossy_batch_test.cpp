// The SIMD glossy stage (integrators/glossy_batch.h) on every SIMD target the CPU has:
// - its kernel against the scalar pieces PathEstimator::step runs for the metal and plastic
//   mixture (Bsdf::eval and sample, AreaLight::sample and EnvironmentLight::sample,
//   powerHeuristic, spawnRay and spawnRayTo), bit for bit, on random vertices: metal, plastic
//   and their blends, roughness from mirrors (delta metal and coat beside Lambert) to past 1,
//   wo above and below n, each lobe chosen, invalid samples (microsurface shadowing, a lobe of
//   probability 0), and light choices of a triangle, the constant environment or none;
// - whole renders of random scenes through `path` (the wavefront, which defers its metal and
//   plastic vertices to the stage) against `path-scalar`, bit for bit.
#include "integrators/glossy_batch.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/ray.h"
#include "core/simd_lanes.h"
#include "materials/bsdf.h"
#include "tests/integrators/shading_stage_test.h"
#include "tests/scene_builder.h"
#include "tests/simd_targets.h"

namespace tray {
namespace {

using test::expectSameBits;
using test::randomTriangle;
using test::randomUnit;

/// Emissive triangles (some double-sided) under a constant environment, beside a point, a spot
/// and a directional light.
Scene emittersUnderSky(std::mt19937_64& rng, int count) {
  Scene scene;
  std::uniform_real_distribution<float> le(0.0f, 5.0f);
  for (int k = 0; k < count; ++k) {
    Material m = test::diffuse(Color(0.5f));
    m.emissive = Color(le(rng), le(rng), k % 3 == 0 ? 0.0f : le(rng));
    m.doubleSided = k % 2 == 0;
    test::addMeshInstance(
        scene, test::addMesh(scene, randomTriangle(rng, test::addMaterial(scene, m))), Mat4());
  }
  scene.environment.background = {0.3f, 0.5f, 0.8f};
  test::addPunctualLights(scene);
  return scene;
}

/// The material of entry q as step() would have evaluated it.
ShadingMaterial materialOf(const ShadingLanes& m, size_t q) {
  ShadingMaterial sm = ShadingMaterial::of(test::diffuse(m.albedo[q]), m.n[q]);
  sm.metallic = m.metallic[q], sm.roughness = m.roughness[q];
  return sm;
}

/// A random metal, plastic or blend of the two that the stage takes: edge values every few.
void randomMaterial(std::mt19937_64& rng, ShadingLanes& m, size_t q) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  do {
    const float metallic[] = {0.0f, 1.0f, u01(rng), 1.3f, -0.2f, 0.5f};
    // 0.04: alpha 0.0016, just rough; 0.02: alpha 0.0004, mirrors (delta metal and coat).
    const float roughness[] = {u01(rng), 0.04f, 1.0f, 0.95f, 1.2f, 0.5f * u01(rng), 0.02f};
    m.metallic[q] = metallic[std::uniform_int_distribution<int>(0, 5)(rng)];
    m.roughness[q] = roughness[std::uniform_int_distribution<int>(0, 6)(rng)];
    m.albedo[q] = {u01(rng), q % 4 == 0 ? 0.0f : u01(rng), u01(rng)};
    if (q % 17 == 0) m.albedo[q] = Color(0.0f);  // a black plastic: only its coat reflects
  } while (!Bsdf::isGgxMixture(materialOf(m, q)));
  const float eta[] = {1.5f, 1.0f / 1.5f, 1.0f + 2.0f * u01(rng), 1.0f};
  m.eta[q] = eta[q % 4];
}

/// One random glossy vertex in entry q of `m`, its light `light` (remembered in m.path).
void randomVertex(std::mt19937_64& rng, const MatteBatch& batch, const LightSet& lights,
                  ShadingLanes& m, size_t q) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), u(-3.0f, 3.0f);
  m.p[q] = {u(rng), u(rng), u(rng)};
  m.ng[q] = randomUnit(rng);
  m.n[q] = q % 5 == 0 ? -m.ng[q] : randomUnit(rng);
  m.wo[q] = randomUnit(rng);                                               // above or below n
  if (q % 10 == 3) m.wo[q] = normalize(m.n[q] + 0.05f * randomUnit(rng));  // near the normal
  randomMaterial(rng, m, q);
  m.beta[q] = {u01(rng) * 3, u01(rng), u01(rng)};
  m.lightDraw[q] = {u01(rng), u01(rng)};
  m.bsdfDraw[q] = q % 7 == 0 ? Vec2{0.5f, 0.5f} : Vec2{u01(rng), u01(rng)};  // the disk's centre
  m.lobeDraw[q] = u01(rng);
  m.pmf[q] = q % 9 == 0 ? 1.0f : u01(rng);
  const int light = std::uniform_int_distribution<int>(0, int(lights.size()) - 1)(rng);
  m.emitter[q] = q % 13 == 0 ? int32_t(kNoLightChosen) : batch.choice(light);
  m.path[q] = uint32_t(light);
}

/// What the comparisons met, so that the test can tell it compared each case.
struct Met {
  int vertices = 0, litTriangle = 0, litEnvironment = 0, litPunctual = 0, unlit = 0, sampled = 0,
      invalid = 0, mirrored = 0;
};

/// Entry q's outputs against the scalar pieces step() runs.
void compareVertex(const LightSet& lights, const ShadingLanes& m, size_t q, Met& met) {
  SCOPED_TRACE(testing::Message() << "metallic " << m.metallic[q] << ", roughness "
                                  << m.roughness[q] << ", eta " << m.eta[q]);
  const Bsdf bsdf(materialOf(m, q), m.n[q], m.eta[q]);
  bool infinite;
  const bool punctual = m.emitter[q] != kNoLightChosen && lights.light(m.path[q]).isDelta();
  if (test::compareLightSample(lights, bsdf, m, q, infinite))
    ++(punctual ? met.litPunctual : infinite ? met.litEnvironment : met.litTriangle);
  else
    ++met.unlit;
  const BsdfSample bs = bsdf.sample(m.wo[q], m.lobeDraw[q], m.bsdfDraw[q]);
  expectSameBits(m.pdf[q], bs.pdf, "pdf", q);
  ++met.vertices;
  if (!(bs.pdf > 0)) {
    ++met.invalid;
    return;
  }
  EXPECT_EQ(bool(m.deltaSample[q]), bs.delta) << q;
  ++(bs.delta ? met.mirrored : met.sampled);
  const Color beta = m.beta[q] * (bs.f * (std::fabs(dot(bs.wi, m.n[q])) / bs.pdf));
  expectSameBits(m.nextBeta[q], beta, "throughput", q);
  const Ray next = spawnRay(m.p[q], m.ng[q], bs.wi, 0.0f);
  expectSameBits(m.rayOrigin[q], next.o, "ray origin", q);
  expectSameBits(m.rayDir[q], next.d, "ray direction", q);
}

TEST(GlossyBatch, KernelIsTheScalarStepBitForBit) {
  std::mt19937_64 rng(17);
  const Scene scene = emittersUnderSky(rng, 4);
  const LightSet lights(scene);
  const MatteBatch matte(lights);
  const GlossyBatch batch(matte);
  ASSERT_EQ(lights.size(), 8u);  // four triangles, three punctual lights and the sky
  ASSERT_GE(lights.constantEnvironment(), 0);
  if (!hasSimdTarget()) GTEST_SKIP() << "no SIMD target: the wavefront keeps to scalar code";
  ASSERT_TRUE(matte.useful());
  test::onEverySimdTarget(1000, [&] {
    Met met;
    ShadingLanes m;
    for (int wave = 0; wave < 40 && !testing::Test::HasFailure(); ++wave) {
      const size_t count = std::uniform_int_distribution<size_t>(1, 100)(rng);  // partial vectors
      m.reset(count);
      for (m.count = 0; m.count < count; ++m.count) randomVertex(rng, matte, lights, m, m.count);
      batch.compute(m);
      for (size_t q = 0; q < count; ++q) compareVertex(lights, m, q, met);
    }
    // Every case was compared, not only skipped.
    EXPECT_GT(met.litTriangle, met.vertices / 20);
    EXPECT_GT(met.litEnvironment, met.vertices / 20);
    EXPECT_GT(met.litPunctual, met.vertices / 20);
    EXPECT_GT(met.unlit, met.vertices / 20);
    EXPECT_GT(met.sampled, met.vertices / 2);
    EXPECT_GT(met.invalid, 0);
    EXPECT_GT(met.mirrored, met.vertices / 50);
    return met.vertices;
  });
}

TEST(GlossyBatch, TakesMetalAndPlasticOnly) {
  // The lone Lambert lobe is the matte stage's; delta lobes, glass, layers and tints stay
  // with the scalar code.
  ShadingMaterial sm = ShadingMaterial::of(test::diffuse(Color(0.5f)), Vec3(0, 0, 1));
  EXPECT_FALSE(Bsdf::isGgxMixture(sm));  // metallic 0, roughness 1: Lambert
  sm.roughness = 0.5f;
  EXPECT_TRUE(Bsdf::isGgxMixture(sm));  // plastic
  sm.metallic = 1.0f;
  EXPECT_TRUE(Bsdf::isGgxMixture(sm));  // metal
  sm.roughness = 0.01f;
  EXPECT_FALSE(Bsdf::isGgxMixture(sm));  // alpha 1e-4: a mirror alone (no light sample)
  sm.metallic = 0.5f;
  EXPECT_TRUE(Bsdf::isGgxMixture(sm));  // mirrors beside a Lambert lobe
  sm.metallic = 0.0f, sm.baseColor = Color(0.0f);
  EXPECT_FALSE(Bsdf::isGgxMixture(sm));  // a black plastic's mirror coat alone
  sm.metallic = 1.0f, sm.baseColor = Color(0.5f), sm.roughness = 0.5f;
  for (const auto& change : std::vector<void (*)(ShadingMaterial&)>{
           [](ShadingMaterial& s) { s.transmission = 0.5f; },
           [](ShadingMaterial& s) { s.clearcoat = 0.5f; },
           [](ShadingMaterial& s) { s.sheenColor = Color(0.2f); },
           [](ShadingMaterial& s) { s.specular = 0.5f; },
           [](ShadingMaterial& s) { s.specularColor = Color(0.5f, 1.0f, 1.0f); },
           [](ShadingMaterial& s) { s.roughness = std::nanf(""); }}) {
    ShadingMaterial other = sm;
    change(other);
    EXPECT_FALSE(Bsdf::isGgxMixture(other));
  }
  sm.metallic = 0.0f, sm.roughness = 1.0f, sm.baseColor = Color(0.0f);
  EXPECT_FALSE(Bsdf::isGgxMixture(sm));  // no lobe scatters
}

/// A random scene of metal, plastic, mirror and matte triangles under emissive ones and a sky,
/// with a glass sphere (the delta stage's) or a point light (the scalar code's) in some.
Scene randomScene(std::mt19937_64& rng, int index) {
  Scene scene = emittersUnderSky(rng, 2);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int k = 0; k < 12; ++k) {
    Material m = test::diffuse(Color(u01(rng), u01(rng), u01(rng)));
    m.metallic = k % 3 == 0 ? 1.0f : k % 3 == 1 ? 0.0f : u01(rng);
    m.roughness = k % 4 == 3 ? 0.01f : 0.05f + 0.9f * u01(rng);  // some mirrors
    test::addMeshInstance(
        scene, test::addMesh(scene, randomTriangle(rng, test::addMaterial(scene, m))), Mat4());
  }
  Material floorMaterial = test::diffuse(Color(0.7f));
  floorMaterial.roughness = 0.3f;  // a glossy plastic floor
  test::addMeshInstance(
      scene, test::addMesh(scene, test::quadMesh(4.0f, test::addMaterial(scene, floorMaterial))),
      Mat4::translate({0, -2.5f, 0}));
  if (index % 3 == 1) {
    Material glass = test::diffuse(Color(1.0f));
    glass.transmission = 1.0f, glass.roughness = 0.0f;
    test::addSphere(scene, {0, 0.5f, 1.5f}, 0.5f, test::addMaterial(scene, glass));
  }
  if (index % 3 == 2) scene.lights.push_back(test::pointLight({1, 3, 1}, Color(20.0f)));
  scene.cameras.push_back(test::lookAt({0.5f, 1.0f, 7.0f}, {0, 0, 0}));
  return scene;
}

TEST(GlossyBatch, RandomScenesRenderAsTheScalarPathTracer) {
  if (!hasSimdTarget()) GTEST_SKIP() << "no SIMD target: the wavefront keeps to scalar code";
  test::randomScenesOnEveryTarget(71, randomScene);
}

}  // namespace
}  // namespace tray

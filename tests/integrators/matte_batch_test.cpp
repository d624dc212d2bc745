// The SIMD matte stage (integrators/matte_batch.h) on every SIMD target the CPU has:
// - its kernel against the scalar pieces PathEstimator::step runs for a lone Lambert lobe and
//   a triangle or rectangle light (sampled by area, by solid angle or either: every
//   --triangle-sampling mode) or the constant environment (AreaLight::sample,
//   EnvironmentLight::sample, Bsdf::eval and sample, powerHeuristic, spawnRayTo, spawnRay), bit for
//   bit, on random vertices including the edge cases (no light chosen, lights facing away,
//   receivers below the light's plane, the disk map's centre, black channels);
// - whole renders of random scenes through `path` (the wavefront, which defers its matte
//   vertices to the stage) against `path-scalar`, bit for bit, with other lights and
//   materials mixed in that the stage leaves to the scalar code.
#include "integrators/matte_batch.h"

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

/// Emissive triangles: random radiance (one black), some double-sided; under a constant
/// environment and beside a point, a spot and a directional light when `sky`.
Scene emitters(std::mt19937_64& rng, int count, bool sky) {
  Scene scene;
  std::uniform_real_distribution<float> le(0.0f, 5.0f);
  for (int k = 0; k < count; ++k) {
    Material m = test::diffuse(Color(0.5f));
    m.emissive = k == 1 ? Color(0.0f) : Color(le(rng), le(rng), k % 3 == 0 ? 0.0f : le(rng));
    m.doubleSided = k % 2 == 0;
    test::addMeshInstance(
        scene, test::addMesh(scene, randomTriangle(rng, test::addMaterial(scene, m))), Mat4());
  }
  if (sky) scene.environment.background = {0.3f, 0.5f, 0.8f};
  if (sky) test::addPunctualLights(scene);
  return scene;
}

/// One random matte vertex in entry q of `m`: edge cases every few entries.
void randomVertex(std::mt19937_64& rng, const MatteBatch& batch, size_t lights, ShadingLanes& m,
                  size_t q) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), u(-3.0f, 3.0f);
  m.p[q] = {u(rng), u(rng), u(rng)};
  m.ng[q] = randomUnit(rng);
  m.n[q] = q % 5 == 0 ? -m.ng[q] : randomUnit(rng);
  m.wo[q] = randomUnit(rng);  // above or below n
  m.albedo[q] = {u01(rng), q % 4 == 0 ? 0.0f : u01(rng), u01(rng) + 0.01f};
  m.beta[q] = {u01(rng) * 3, u01(rng), u01(rng)};
  m.lightDraw[q] = {u01(rng), u01(rng)};
  m.bsdfDraw[q] = q % 7 == 0 ? Vec2{0.5f, 0.5f} : Vec2{u01(rng), u01(rng)};  // the disk's centre
  if (q % 11 == 0) m.bsdfDraw[q].x = 0.5f;  // ox == 0: the y wedge divides by zero
  m.pmf[q] = q % 9 == 0 ? 1.0f : u01(rng);
  const int light = std::uniform_int_distribution<int>(0, int(lights) - 1)(rng);
  m.emitter[q] = q % 13 == 0 ? -1 : batch.choice(light);
  m.path[q] = uint32_t(light);  // remembered for the scalar side
}

/// Entry q's outputs against the scalar pieces step() runs; returns 1 when it was lit, and
/// counts in environmentLit when by the environment.
int compareVertex(const LightSet& lights, const ShadingLanes& m, size_t q, int& environmentLit,
                  int& punctualLit) {
  Material material = test::diffuse(m.albedo[q]);
  const Bsdf bsdf(material, m.n[q], 1.5f);
  EXPECT_TRUE(bsdf.lambertOnly());
  bool infinite;
  const bool lit = test::compareLightSample(lights, bsdf, m, q, infinite);
  const bool punctual = m.emitter[q] != kNoLightChosen && lights.light(m.path[q]).isDelta();
  environmentLit += lit && infinite && !punctual;
  punctualLit += lit && punctual;
  const BsdfSample bs = bsdf.sample(m.wo[q], 0.0f, m.bsdfDraw[q]);
  expectSameBits(m.pdf[q], bs.pdf, "pdf", q);
  EXPECT_GT(m.pdf[q], 0.0f) << q;
  const Color beta = m.beta[q] * (bs.f * (std::fabs(dot(bs.wi, m.n[q])) / bs.pdf));
  expectSameBits(m.nextBeta[q], beta, "throughput", q);
  const Ray next = spawnRay(m.p[q], m.ng[q], bs.wi, 0.0f);
  expectSameBits(m.rayOrigin[q], next.o, "ray origin", q);
  expectSameBits(m.rayDir[q], next.d, "ray direction", q);
  return lit;
}

/// What compareWaves compared: vertices, and those lit by any light, the sky, a punctual light.
struct WaveCounts {
  int compared = 0, lit = 0, environmentLit = 0, punctualLit = 0;
};

/// 40 waves of random vertices (1 to 100 each: partial vectors) through the stage, each vertex
/// compared with the scalar step (compareVertex); stops at the first failure.
WaveCounts compareWaves(std::mt19937_64& rng, const LightSet& lights, const MatteBatch& batch) {
  WaveCounts n;
  ShadingLanes m;
  for (int wave = 0; wave < 40 && !testing::Test::HasFailure(); ++wave) {
    const size_t count = std::uniform_int_distribution<size_t>(1, 100)(rng);
    m.reset(count);
    for (m.count = 0; m.count < count; ++m.count)
      randomVertex(rng, batch, lights.size(), m, m.count);
    batch.compute(m);
    for (size_t q = 0; q < count; ++q)
      n.lit += compareVertex(lights, m, q, n.environmentLit, n.punctualLit), ++n.compared;
  }
  return n;
}

/// Every way of sampling the triangles (--triangle-sampling): the random receivers see them
/// under solid angles on both sides of auto's bounds.
class MatteBatchModes : public testing::TestWithParam<TriangleSampling> {};

TEST_P(MatteBatchModes, KernelIsTheScalarStepBitForBit) {
  std::mt19937_64 rng(16);
  const Scene scene = emitters(rng, 6, true);
  const LightSet lights(scene, LightSamplerKind::kBvh, GetParam());
  const MatteBatch batch(lights);
  ASSERT_EQ(lights.size(), 9u);  // the black triangle is not a light; the sky and 3 punctual are
  if (!hasSimdTarget()) GTEST_SKIP() << "no SIMD target: the wavefront keeps to scalar code";
  ASSERT_TRUE(batch.useful());
  test::onEverySimdTarget(1000, [&] {
    const WaveCounts n = compareWaves(rng, lights, batch);
    const int compared = n.compared, lit = n.lit, environmentLit = n.environmentLit,
              punctualLit = n.punctualLit;
    EXPECT_GT(lit, compared / 5);  // the light sample's arithmetic is compared, not only skipped
    EXPECT_LT(lit, compared);      // and so are the unlit cases
    EXPECT_GT(environmentLit, compared / 40);  // and the sky's samples (1 light of 9)
    EXPECT_GT(punctualLit, compared / 20);     // and the punctual lights' (no MIS weight)
    return compared;
  });
}
/// A rectangle of two triangles (lights/quad_lights.h finds it where triangles may be sampled
/// by solid angle): random centre, size and orientation, front face along u x v.
void addEmissiveRectangle(Scene& scene, std::mt19937_64& rng, bool doubleSided) {
  std::uniform_real_distribution<float> u(-2.0f, 2.0f), size(0.3f, 2.0f);
  const Vec3 a = randomUnit(rng), b = normalize(cross(a, randomUnit(rng)));
  const Vec3 c(u(rng), u(rng), u(rng)), ea = size(rng) * a, eb = size(rng) * b;
  Material m = test::diffuse(Color(0.5f));
  m.emissive = Color(2.0f, 3.0f, 1.5f);
  m.doubleSided = doubleSided;
  TriangleMesh quad;
  quad.positions = {c, c + ea, c + eb, c + ea + eb};
  quad.indices = {0, 1, 2, 2, 1, 3};
  quad.material = test::addMaterial(scene, m);
  test::addMeshInstance(scene, test::addMesh(scene, std::move(quad)), Mat4());
}

TEST_P(MatteBatchModes, RectanglesAreTheScalarStepBitForBit) {
  // Rectangle rows (a negative area in the table) mixed with triangle rows in one vector: the
  // stage's SampleTriangleOrRectangle against AreaLight::sample of either kind.
  std::mt19937_64 rng(41);
  Scene scene = emitters(rng, 3, true);
  addEmissiveRectangle(scene, rng, false);
  addEmissiveRectangle(scene, rng, true);
  const LightSet lights(scene, LightSamplerKind::kBvh, GetParam());
  EXPECT_EQ(lights.rectangleCount(), GetParam() == TriangleSampling::kArea ? 0u : 2u);
  const MatteBatch batch(lights);
  if (!hasSimdTarget()) GTEST_SKIP() << "no SIMD target: the wavefront keeps to scalar code";
  ASSERT_TRUE(batch.useful());
  test::onEverySimdTarget(1000, [&] {
    const WaveCounts n = compareWaves(rng, lights, batch);
    const int compared = n.compared, lit = n.lit;
    EXPECT_GT(lit, compared / 5);
    return compared;
  });
}

INSTANTIATE_TEST_SUITE_P(TriangleSampling, MatteBatchModes,
                         testing::Values(TriangleSampling::kAuto, TriangleSampling::kArea,
                                         TriangleSampling::kSolidAngle));

/// A random scene: matte triangles under emissive ones, a floor, and in some a metal (the glossy
/// stage's), an emissive sphere (the scalar code's) or a point light.
Scene randomScene(std::mt19937_64& rng, int index) {
  Scene scene = emitters(rng, 3, index % 2 == 1);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int k = 0; k < 12; ++k) {
    Material m = test::diffuse(Color(u01(rng), u01(rng), u01(rng)));
    if (index % 2 == 1 && k == 0) m.metallic = 1, m.roughness = 0.3f;
    test::addMeshInstance(
        scene, test::addMesh(scene, randomTriangle(rng, test::addMaterial(scene, m))), Mat4());
  }
  const int floor = test::addMaterial(scene, test::diffuse(Color(0.7f)));
  test::addMeshInstance(scene, test::addMesh(scene, test::quadMesh(4.0f, floor)),
                        Mat4::translate({0, -2.5f, 0}));
  if (index % 3 == 1) {
    Material glow = test::diffuse(Color(0.2f));
    glow.emissive = Color(3.0f);
    test::addSphere(scene, {0, 2.5f, 0}, 0.5f, test::addMaterial(scene, glow));
  }
  if (index % 3 == 2) scene.lights.push_back(test::pointLight({1, 3, 1}, Color(20.0f)));
  scene.cameras.push_back(test::lookAt({0.5f, 1.0f, 7.0f}, {0, 0, 0}));
  return scene;
}

TEST(MatteBatch, RandomScenesRenderAsTheScalarPathTracer) {
  if (!hasSimdTarget()) GTEST_SKIP() << "no SIMD target: the wavefront keeps to scalar code";
  test::onEverySimdTarget(5, [] {
    // The stage ran: for most vertices where only matte surfaces and triangle lights are in
    // the scene.
    return test::compareRandomScenes(61, randomScene, [](int index, uint64_t secondary) {
      return index % 6 == 0 ? secondary / 2 : 0u;
    });
  });
}

}  // namespace
}  // namespace tray

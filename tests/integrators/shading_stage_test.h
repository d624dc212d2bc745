#pragma once
// What the SIMD shading stages' tests share (tests/integrators/matte_batch_test.cpp,
// glossy_batch_test.cpp): random inputs, bit comparisons, and whole renders of random scenes
// through `path` (the wavefront, which defers vertices to the stages) against `path-scalar`.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <functional>
#include <random>

#include "core/math.h"
#include "core/ray.h"
#include "integrators/shading_lanes.h"
#include "lights/light_set.h"
#include "materials/bsdf.h"
#include "tests/integrators/render_job.h"
#include "tests/scene_builder.h"
#include "tests/simd_targets.h"

namespace tray::test {

inline Vec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<float> g;
  for (;;) {
    const Vec3 v{g(rng), g(rng), g(rng)};
    if (length(v) > 1e-3f) return normalize(v);
  }
}

/// A mesh of one triangle with random corners in [-2, 2]^3 and material `material`.
inline TriangleMesh randomTriangle(std::mt19937_64& rng, int material) {
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  TriangleMesh m;
  for (int k = 0; k < 3; ++k) m.positions.push_back({u(rng), u(rng), u(rng)});
  m.indices = {0, 1, 2};
  m.material = material;
  return m;
}

inline void expectSameBits(float got, float want, const char* what, size_t q) {
  EXPECT_EQ(std::bit_cast<uint32_t>(got), std::bit_cast<uint32_t>(want))
      << what << " of vertex " << q << ": " << got << " vs " << want;
}
inline void expectSameBits(const Vec3& got, const Vec3& want, const char* what, size_t q) {
  for (int a = 0; a < 3; ++a) expectSameBits(got[a], want[a], what, q);
}

/// Entry q's next-event outputs against what nextEvent computes with `bsdf`: the chosen
/// light's sample (m.path[q] holds its index), the BSDF's value and pdf toward it, the shadow
/// ray and the estimate. Returns whether it was lit; `infinite`: by the environment or a
/// directional light (an unbounded shadow ray).
inline bool compareLightSample(const LightSet& lights, const Bsdf& bsdf, const ShadingLanes& m,
                               size_t q, bool& infinite) {
  const LightSampleContext ctx{m.p[q], m.n[q], false, false};
  LightSample ls;
  if (m.emitter[q] != kNoLightChosen) {
    ls = lights.light(m.path[q]).sample(ctx, m.lightDraw[q]);
    ls.pdf *= m.pmf[q];
  }
  infinite = ls.infinite;
  bool lit = false;
  if (ls.valid() && !isBlack(ls.L)) {
    float bsdfPdf;
    const Color f = bsdf.eval(m.wo[q], ls.wi, bsdfPdf) * std::fabs(dot(ls.wi, m.n[q]));
    if (!isBlack(f)) {
      lit = true;
      const Ray shadow = ls.infinite ? spawnRay(m.p[q], m.ng[q], ls.wi, 0.0f)
                                     : spawnRayTo(m.p[q], m.ng[q], ls.p, 0.0f);
      expectSameBits(m.shadowOrigin[q], shadow.o, "shadow origin", q);
      expectSameBits(m.shadowDir[q], shadow.d, "shadow direction", q);
      EXPECT_EQ(bool(m.shadowUnbounded[q]), ls.infinite) << q;
      const float w = ls.delta ? 1.0f : powerHeuristic(ls.pdf, bsdfPdf);
      expectSameBits(m.contribution[q], m.beta[q] * f * ls.L * (w / ls.pdf), "contribution", q);
    }
  }
  EXPECT_EQ(bool(m.lit[q]), lit) << q;
  return lit;
}

/// Six random scenes (makeScene(rng, index)) rendered by `path-scalar` and `path`: every
/// pixel and the ray counts the same, and the stages shaded more than minimumSimd(index,
/// secondary rays) vertices (the scalar driver none). Returns the scenes compared.
inline int compareRandomScenes(uint64_t seed,
                               const std::function<Scene(std::mt19937_64&, int)>& makeScene,
                               const std::function<uint64_t(int, uint64_t)>& minimumSimd) {
  std::mt19937_64 rng(seed);
  int compared = 0;
  for (int index = 0; index < 6 && !testing::Test::HasFailure(); ++index) {
    const Scene scene = makeScene(rng, index);
    Job job;
    job.size = 20, job.spp = 4, job.seed = uint64_t(index);
    const Render scalar = render(scene, job);
    job.integrator = "path";
    const Render wave = render(scene, job);
    EXPECT_EQ(differingValues(scalar.film, wave.film), 0u) << "scene " << index;
    EXPECT_EQ(scalar.stats.rays.shadowRays, wave.stats.rays.shadowRays) << index;
    EXPECT_EQ(scalar.stats.rays.secondaryRays, wave.stats.rays.secondaryRays) << index;
    EXPECT_EQ(scalar.stats.rays.simdVertices, 0u);
    EXPECT_GT(wave.stats.rays.simdVertices, minimumSimd(index, wave.stats.rays.secondaryRays))
        << index;
    ++compared;
  }
  return compared;
}

/// compareRandomScenes on every SIMD target, the stages shading at least a third as many
/// vertices as there were secondary rays (most vertices that hit something).
inline void randomScenesOnEveryTarget(uint64_t seed,
                                      const std::function<Scene(std::mt19937_64&, int)>& make) {
  onEverySimdTarget(5, [&] {
    return compareRandomScenes(seed, make, [](int, uint64_t secondary) { return secondary / 3; });
  });
}

}  // namespace tray::test

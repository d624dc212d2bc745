// Issue 37: "the light BVH's importance and the chosen sampling agree on the Cornell box and
// on many-light scenes", made concrete (docs/path-tracing.md, "Light BVH and per-emitter
// sampling"). For receivers in each scene, with the per-emitter sampling that
// --triangle-sampling auto chooses there:
//  1. Choice against contribution. E_j, emitter j's unoccluded contribution to a Lambert
//     receiver (the luminance of Le |cos| / pdf averaged over 64 of j's own samples), against
//     the BVH's pmf_j. Next-event estimation picks one emitter and returns E_J / pmf_J, whose
//     second moment sum_j E_j^2 / pmf_j is smallest, (sum_j E_j)^2, for pmf_j proportional to
//     E_j; their ratio, the chooser's efficiency in (0, 1], is held above a bound per scene,
//     and no emitter that gives 2% or more of a receiver's light may be chosen more than a
//     bound times less often than its share (receivers with at least 1% of the mean light).
//     Measured with pbrt-v4's importance (distance clamped to the box's bounding radius):
//     efficiency 0.26-0.28 on the many-light scenes; with Cycles' clamp to half that radius
//     (core/light_bounds.cpp) 0.405-0.415; with that and a child near the receiver weighed by
//     its two halves (BvhLightSampler::weight) and whole-box culls 0.519-0.553, the bound
//     below, which either of the first two steps alone fails. The most neglected emitter is
//     still chosen up to 52x (triangles) / 60x (quads) less often than its share (pbrt: 42x
//     / 53x; the clamp alone 62x / 103x; without the culls 81x / 60x):
//     receivers inside the lamps' slab with any normal, next to a spot whose narrow beam
//     shares a cone with the lamps (docs/bench/light-bvh-importance-2026-12-07.md). Found
//     and fixed: the Cornell box's quad as two triangles split the choice evenly where a
//     receiver sees mostly one.
//  2. The combined pdf. Every light sample (BVH choice x the emitter's pdf) equals the pdf that
//     MIS computes for a BSDF-sampled ray to the same point: LightSet::pdf of the light that
//     lightAt names for the triangle the point lies on (rectangles: either triangle). Found
//     and fixed: a receiver 0.03 below the panel's plane, 3 away, had them 0.8% apart (the
//     spherical rectangle's float precision edge on; preciseRectangleSolidAngle).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "gltf/gltf_loader.h"
#include "lights/light_set.h"
#include "tests/light_scenes.h"

namespace tray {
namespace {

struct Receiver {
  Vec3 p, n;
};

/// Receivers: points in the scene's box (shrunk by 2%), half on its floor facing up, half
/// anywhere with a random normal.
std::vector<Receiver> receivers(const Scene& scene, int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const Bounds3 b = scene.bounds();
  const Vec3 lo = b.lo + 0.02f * b.diagonal(), size = 0.96f * b.diagonal();
  std::vector<Receiver> out;
  for (int i = 0; i < count; ++i) {
    Vec3 p = lo + Vec3(u01(rng) * size.x, u01(rng) * size.y, u01(rng) * size.z);
    Vec3 n(0, 1, 0);
    if (i % 2 == 0) {
      p.y = b.lo.y + 1e-3f * size.y;
    } else {
      const float z = 2 * u01(rng) - 1, phi = 2 * kPi * u01(rng), r = std::sqrt(1 - z * z);
      n = Vec3(r * std::cos(phi), z, r * std::sin(phi));
    }
    out.push_back({p, n});
  }
  return out;
}

struct Agreement {
  double efficiency = 0;  ///< mean over receivers with light
  double worstEfficiency = 1;
  /// The largest share_j / pmf_j over emitters giving >= 2% of a receiver's light: how many
  /// times less often than its share the BVH chooses the most neglected one.
  double worstUnder = 0;
};

Agreement agreement(const Scene& scene, TriangleSampling mode, int count) {
  const LightSet lights(scene, LightSamplerKind::kBvh, mode);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const std::vector<Receiver> rs = receivers(scene, count, 29);
  std::vector<std::vector<double>> E(rs.size(), std::vector<double>(lights.size(), 0.0));
  std::vector<double> total(rs.size(), 0.0);
  double mean = 0;
  for (size_t i = 0; i < rs.size(); ++i) {
    const LightSampleContext ctx{rs[i].p, rs[i].n, false, false};
    for (size_t j = 0; j < lights.size(); ++j) {
      const Light& l = lights.light(j);
      if (!(l.power() > 0)) continue;
      const int m = (l.flags() & kLightArea) ? 64 : 1;
      for (int k = 0; k < m; ++k) {
        const LightSample s = l.sample(ctx, Vec2{u01(rng), u01(rng)});
        if (s.valid() && s.pdf > 0)
          E[i][j] += double(luminance(s.L)) * std::max(0.0f, dot(rs[i].n, s.wi)) / s.pdf / m;
      }
      total[i] += E[i][j];
    }
    mean += total[i] / double(rs.size());
  }
  // Receivers that get at least 1% of the mean light: a receiver seeing every light edge on
  // (1e-7 of the mean) may have any choice without a visible effect.
  Agreement a;
  int lit = 0;
  for (size_t i = 0; i < rs.size(); ++i) {
    if (!(total[i] >= 0.01 * mean)) continue;
    ++lit;
    const LightSampleContext ctx{rs[i].p, rs[i].n, false, false};
    double second = 0;
    for (size_t j = 0; j < lights.size(); ++j) {
      if (!(E[i][j] > 0)) continue;
      const double pmf = lights.pmf(ctx, int(j)), share = E[i][j] / total[i];
      second += pmf > 0 ? E[i][j] * E[i][j] / pmf : INFINITY;
      if (share >= 0.02) a.worstUnder = std::max(a.worstUnder, pmf > 0 ? share / pmf : INFINITY);
    }
    const double eff = total[i] * total[i] / second;
    a.efficiency += eff;
    a.worstEfficiency = std::min(a.worstEfficiency, eff);
  }
  a.efficiency /= std::max(lit, 1);
  return a;
}

Scene cornell() {
  return loadGltf(std::string(TRAY_SHARED_DIR) + "/reference/cornell-box.gltf");
}

TEST(LightBvhAgreement, CornellLightIsOneRectangle) {
  // The shared Cornell box's light is a quad of two triangles: found as one rectangle where
  // triangles may be sampled by solid angle, kept as two by area.
  const Scene scene = cornell();
  EXPECT_EQ(LightSet(scene, LightSamplerKind::kBvh, TriangleSampling::kAuto).rectangleCount(), 1u);
  EXPECT_EQ(LightSet(scene, LightSamplerKind::kBvh, TriangleSampling::kArea).rectangleCount(), 0u);
  EXPECT_EQ(LightSet(scene, LightSamplerKind::kBvh, TriangleSampling::kArea).triangleCount(), 2u);
}

TEST(LightBvhAgreement, ChoiceFollowsTheContribution) {
  struct Named {
    const char* name;
    Scene scene;
    double minEfficiency, maxUnder;
  };
  // Bounds: past the measured values (docs/path-tracing.md; Cornell 0.971 and 2.0x by area,
  // many lights 0.519-0.553 and 52-60x) by a margin for other seeds; pbrt-v4's importance
  // (0.263-0.283) and the clamp without the near children (0.405-0.415) fail them.
  Named scenes[] = {{"cornell", cornell(), 0.9, 3},
                    {"many lights", test::manyLightsScene(), 0.47, 75},
                    {"many quad lights", test::manyLightsScene(true), 0.47, 75}};
  for (Named& s : scenes)
    for (TriangleSampling mode : {TriangleSampling::kArea, TriangleSampling::kAuto}) {
      const Agreement a = agreement(s.scene, mode, 200);
      std::printf("%-16s %-4s efficiency mean %.3f worst %.3f, most neglected emitter %.1fx\n",
                  s.name, mode == TriangleSampling::kArea ? "area" : "auto", a.efficiency,
                  a.worstEfficiency, a.worstUnder);
      EXPECT_GT(a.efficiency, s.minEfficiency) << s.name;
      EXPECT_LT(a.worstUnder, s.maxUnder) << s.name;
      // The Cornell box's light is one quad: as two triangles (area) the BVH splits its choice
      // about evenly between them wherever their bounds look alike, though a receiver near
      // the light's plane sees mostly one (efficiency down to 0.52); as one rectangle (auto)
      // there is one emitter to choose.
      if (std::string(s.name) == "cornell" && mode == TriangleSampling::kAuto) {
        EXPECT_GT(a.worstEfficiency, 0.999);
      }
    }
}

/// The emissive mesh triangle (primitive, triangle) that world point p lies on and whose
/// light is `light`, or false.
bool triangleAt(const Scene& scene, const LightSet& lights, const Vec3& p, int light,
                uint32_t& primitive, uint32_t& triangle) {
  for (uint32_t i = 0; i < scene.primitives.size(); ++i) {
    const Primitive& prim = scene.primitives[i];
    if (prim.kind != Primitive::Kind::kMesh || lights.lightAt(i, 0) < 0) continue;
    const TriangleMesh& mesh = scene.meshes[prim.mesh];
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
      if (lights.lightAt(i, t) != light) continue;
      const uint32_t* idx = &mesh.indices[3 * size_t(t)];
      const Vec3 a = prim.toWorld.point(mesh.positions[idx[0]]);
      const Vec3 e1 = prim.toWorld.point(mesh.positions[idx[1]]) - a;
      const Vec3 e2 = prim.toWorld.point(mesh.positions[idx[2]]) - a, d = p - a;
      const Vec3 n = cross(e1, e2);
      const float n2 = dot(n, n), tol = 1e-4f;
      if (std::fabs(dot(d, n)) > tol * std::sqrt(n2) * std::sqrt(std::sqrt(n2))) continue;
      const float b1 = dot(cross(d, e2), n) / n2, b2 = dot(cross(e1, d), n) / n2;
      if (b1 < -tol || b2 < -tol || b1 + b2 > 1 + tol) continue;
      primitive = i, triangle = t;
      return true;
    }
  }
  return false;
}

TEST(LightBvhAgreement, CombinedPdfIsWhatMisUses) {
  Scene scenes[] = {cornell(), test::manyLightsScene(true), test::panelByAWallScene()};
  for (const Scene& scene : scenes)
    for (TriangleSampling mode :
         {TriangleSampling::kArea, TriangleSampling::kAuto, TriangleSampling::kSolidAngle}) {
      const LightSet lights(scene, LightSamplerKind::kBvh, mode);
      std::mt19937_64 rng(23);
      std::uniform_real_distribution<float> u01(0.0f, 1.0f);
      int checked = 0;
      for (const Receiver& r : receivers(scene, 300, 31)) {
        const LightSampleContext ctx{r.p, r.n, false, false};
        float pmf;
        const int j = lights.choose(ctx, u01(rng), pmf);
        const AreaLight* area = j >= 0 ? lights.areaLight(size_t(j)) : nullptr;
        if (!area || area->isTriangle() == area->isRectangle()) continue;  // meshes only
        const LightSample s = lights.sampleChosen(j, pmf, ctx, Vec2{u01(rng), u01(rng)});
        if (!s.valid()) continue;
        uint32_t prim = 0, tri = 0;
        ASSERT_TRUE(triangleAt(scene, lights, s.p, j, prim, tri)) << j;
        const Vec3 ng = area->triangleData().n;
        const float mis = lights.pdf(lights.lightAt(prim, tri), ctx, s.wi, s.p, ng);
        ASSERT_NEAR(mis / s.pdf, 1.0f, 2e-3f)
            << "light " << j << " triangle " << tri << " mode " << int(mode) << " pmf " << pmf
            << " pmf() " << lights.pmf(ctx, j) << " p " << r.p.x << " " << r.p.y << " " << r.p.z
            << " n " << r.n.x << " " << r.n.y << " " << r.n.z << " light pdf "
            << lights.light(size_t(j)).pdf(ctx, s.wi, s.p, ng) << " sample pdf " << s.pdf / pmf
            << " rect " << area->triangleData().p0.x << " " << area->triangleData().p0.y << " "
            << area->triangleData().p0.z << " e1 " << area->triangleData().e1.x << " "
            << area->triangleData().e1.y << " " << area->triangleData().e1.z << " e2 "
            << area->triangleData().e2.x << " " << area->triangleData().e2.y << " "
            << area->triangleData().e2.z << " sp " << s.p.x << " " << s.p.y << " " << s.p.z;
        ++checked;
      }
      EXPECT_GT(checked, 100);
    }
}

}  // namespace
}  // namespace tray

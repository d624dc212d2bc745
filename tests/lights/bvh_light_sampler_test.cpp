// The light BVH chooser: its probabilities form a distribution at every receiver, sampling
// reports exactly the pmf that MIS later asks for, choices follow the pmf, and a BSDF ray that
// hits an emitter gets the pdf next-event estimation gave the same direction.
#include "lights/bvh_light_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "accel/registry.h"
#include "lights/light_set.h"
#include "tests/light_scenes.h"

namespace tray {
namespace {

using namespace tray::test;

/// Every kind of light: the many-lights scene plus a sun and a sky.
Scene everyKindOfLight() {
  Scene s = manyLightsScene();
  PunctualLightDesc sun;
  sun.type = PunctualLightDesc::Type::kDirectional;
  sun.direction = normalize(Vec3(0.3f, -1, 0.2f));
  sun.intensity = Color(2.0f);
  s.lights.push_back(sun);
  s.environment.background = Color(0.3f);
  return s;
}

std::vector<LightBounds> boundsOf(const LightSet& lights) {
  std::vector<LightBounds> b;
  for (size_t i = 0; i < lights.size(); ++i) b.push_back(lights.light(i).bounds());
  return b;
}

struct Receivers {
  std::mt19937 gen{3};
  float u() { return std::uniform_real_distribution<float>(0, 1)(gen); }
  LightSampleContext next() {
    Vec3 n;
    do n = Vec3(2 * u() - 1, 2 * u() - 1, 2 * u() - 1);
    while (lengthSquared(n) > 1 || lengthSquared(n) < 1e-2f);
    return {{10 * u() - 5, 2.5f * u() - 0.5f, 10 * u() - 5}, normalize(n), false, u() < 0.3f};
  }
};

TEST(BvhLightSampler, PmfsSumToOneAtRandomReceivers) {
  Scene s = everyKindOfLight();
  s.finalize();
  const LightSet lights(s, LightSamplerKind::kBvh);
  ASSERT_GT(lights.size(), 260u);
  Receivers r;
  int none = 0;
  for (int i = 0; i < 400; ++i) {
    const LightSampleContext ctx = r.next();
    double sum = 0;
    for (size_t l = 0; l < lights.size(); ++l) sum += lights.pmf(ctx, int(l));
    if (sum == 0) {  // then sampling finds nothing either
      ++none;
      EXPECT_FALSE(lights.sample(ctx, 0.5f, {0.5f, 0.5f}).valid());
      continue;
    }
    EXPECT_NEAR(sum, 1.0, 1e-4) << "receiver " << i;
  }
  EXPECT_LT(none, 40);
}

TEST(BvhLightSampler, SamplingReportsThePmfThatQueriesGiveBitForBit) {
  Scene s = everyKindOfLight();
  s.finalize();
  const LightSet lights(s, LightSamplerKind::kPower);
  const BvhLightSampler sampler(boundsOf(lights));
  EXPECT_GT(sampler.depth(), 7);
  Receivers r;
  for (int i = 0; i < 2000; ++i) {
    const LightSampleContext ctx = r.next();
    float pmf;
    const int light = sampler.sample(ctx, r.u(), pmf);
    if (light < 0) continue;
    EXPECT_GT(pmf, 0.0f);
    EXPECT_EQ(pmf, sampler.pmf(ctx, light)) << "receiver " << i << ", light " << light;
  }
}

/// The many-lights scene under a sky alone (no sun): the sky is the only infinite light.
Scene manyLightsUnderASky() {
  Scene s = manyLightsScene();
  s.environment.background = Color(0.3f);
  return s;
}

TEST(BvhLightSampler, SamplingGivesTheSkysPmfAsTheEscapeAsksForIt) {
  // What PathEstimator::escape weighs an escaping ray by: pmf(prev, sky), given by the choice
  // made at prev, bit for bit; none (-1) when a sun stands beside the sky at the top level.
  Scene sky = manyLightsUnderASky();
  sky.finalize();
  const LightSet lights(sky, LightSamplerKind::kBvh);
  ASSERT_EQ(lights.infinite().size(), 1u);
  const int skyLight = lights.infinite()[0];
  EXPECT_EQ(lights.escapeLight(), skyLight);
  Receivers r;
  int chosen = 0, skyChosen = 0;
  for (int i = 0; i < 2000; ++i) {
    const LightSampleContext ctx = r.next();
    const float u = r.u();
    float pmf, escapePmf = -2;
    const int light = lights.choose(ctx, u, pmf, escapePmf);
    EXPECT_EQ(escapePmf, lights.pmf(ctx, skyLight)) << "receiver " << i;
    // The same choice and pmf as without it.
    float plainPmf;
    EXPECT_EQ(light, lights.choose(ctx, u, plainPmf)) << "receiver " << i;
    EXPECT_EQ(pmf, plainPmf) << "receiver " << i;
    chosen += light >= 0, skyChosen += light == skyLight;
  }
  EXPECT_GT(chosen, 1000);
  EXPECT_GT(skyChosen, 20);  // both branches of the top level were taken
  EXPECT_LT(skyChosen, chosen - 20);

  Scene sunAndSky = everyKindOfLight();
  sunAndSky.finalize();
  const LightSet both(sunAndSky, LightSamplerKind::kBvh);
  EXPECT_EQ(both.escapeLight(), -1);
  float pmf, escapePmf = 0.5f;
  both.choose(r.next(), 0.5f, pmf, escapePmf);
  EXPECT_EQ(escapePmf, -1.0f);
}

TEST(BvhLightSampler, ChoicesFollowThePmf) {
  Scene s = everyKindOfLight();
  s.finalize();
  const LightSet lights(s, LightSamplerKind::kPower);
  const BvhLightSampler sampler(boundsOf(lights));
  const LightSampleContext ctx{{0.3f, 0, 0.2f}, {0, 1, 0}};
  // Stratified u: each light's share of [0,1) is its pmf, so counts match it to 1/N.
  const int n = 1 << 18;
  std::vector<int> counts(lights.size(), 0);
  for (int i = 0; i < n; ++i) {
    float pmf;
    const int light = sampler.sample(ctx, (float(i) + 0.5f) / n, pmf);
    ASSERT_GE(light, 0);
    ++counts[size_t(light)];
  }
  int chosen = 0;
  for (size_t l = 0; l < lights.size(); ++l) {
    EXPECT_NEAR(counts[l] / double(n), sampler.pmf(ctx, int(l)), 2e-5) << "light " << l;
    chosen += counts[l] > 0;
  }
  EXPECT_GT(chosen, 50);  // not a degenerate distribution
}

TEST(BvhLightSampler, ABsdfRayThatHitsAnEmitterGetsTheNextEventPdf) {
  Scene s = everyKindOfLight();
  s.finalize();
  const LightSet lights(s, LightSamplerKind::kBvh);
  auto accel = makeAccelerator("embree", s);
  Receivers r;
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    // Receivers on the ground, as the path tracer shades them.
    const LightSampleContext ctx{{10 * r.u() - 5, 0, 10 * r.u() - 5}, {0, 1, 0}};
    const LightSample ls = lights.sample(ctx, r.u(), {r.u(), r.u()});
    if (!ls.valid() || ls.delta || ls.infinite) continue;
    Hit hit;
    if (!accel->intersect(spawnRay(ctx.p, ctx.n, ls.wi, 0.0f), hit)) continue;
    const int light = lights.lightAt(hit.primitive, hit.triangle);
    if (light < 0) continue;  // an occluder in between
    const Ray ray = spawnRay(ctx.p, ctx.n, ls.wi, 0.0f);
    const SurfacePoint sp = s.surface(ray, hit);
    if (length(sp.p - ls.p) > 1e-3f) continue;  // another emitter in front of the sampled one
    ++hits;
    EXPECT_NEAR(lights.pdf(light, ctx, ls.wi, sp.p, sp.ng), ls.pdf, 2e-3f * ls.pdf) << i;
  }
  EXPECT_GT(hits, 300);
}

TEST(BvhLightSampler, AChildNearTheReceiverIsWeighedByItsHalves) {
  // Two clusters of two lamps, the receiver beside cluster A (within twice its bounding
  // radius): A's near lamp faces it, A's far lamp faces away, B's two face it from 3 away.
  // A's one box would weigh its strength as if at its centre, whatever its lamps face; its
  // halves give the near lamp alone. The pmf of A's near lamp is then its importance over the
  // sum of its importance and B's (far: B's one box), and A's other lamp gets nothing.
  auto lamp = [](Vec3 c, Vec3 w) {
    Bounds3 box;
    box.extend(c - Vec3(0.05f, 0, 0.05f));
    box.extend(c + Vec3(0.05f, 0, 0.05f));
    return LightBounds::finite(box, w, 1.0f, 1.0f, 0.0f, false);
  };
  const std::vector<LightBounds> bounds = {
      lamp({0, 0.5f, 0}, {0, -1, 0}), lamp({1.5f, 0.3f, 0}, {0, 1, 0}),    // A
      lamp({3, 0.5f, 0}, {0, -1, 0}), lamp({3.2f, 0.5f, 0.2f}, {0, -1, 0})};  // B
  const BvhLightSampler tree(bounds);
  ASSERT_EQ(tree.depth(), 2);
  const LightSampleContext ctx{{0.2f, 0, 0}, {0, 1, 0}};
  const float near = bounds[0].importance(ctx), b = unite(bounds[2], bounds[3]).importance(ctx);
  const float a = unite(bounds[0], bounds[1]).importance(ctx);  // A's box: whole sphere
  EXPECT_EQ(bounds[1].importance(ctx), 0.0f);
  EXPECT_NEAR(tree.pmf(ctx, 0), near / (near + b), 1e-6f);
  EXPECT_GT(std::fabs(tree.pmf(ctx, 0) - a / (a + b)), 1e-3f);  // not A's box
  EXPECT_EQ(tree.pmf(ctx, 1), 0.0f);
  EXPECT_NEAR(tree.pmf(ctx, 0) + tree.pmf(ctx, 2) + tree.pmf(ctx, 3), 1.0f, 1e-5f);
}

TEST(BvhLightSampler, OneLightIsChosenWithProbabilityOneAndNoLightNever) {
  const LightSampleContext ctx{{0, 0, 0}, {0, 1, 0}};
  const BvhLightSampler one({LightBounds::ambient(1.0f)});
  float pmf;
  EXPECT_EQ(one.sample(ctx, 0.99f, pmf), 0);
  EXPECT_EQ(pmf, 1.0f);
  const BvhLightSampler none({});
  EXPECT_EQ(none.sample(ctx, 0.5f, pmf), -1);
  EXPECT_EQ(pmf, 0.0f);
  EXPECT_EQ(none.pmf(ctx, 0), 0.0f);
}

}  // namespace
}  // namespace tray

// LightBounds::importance may be 0 only where a light cannot contribute (the chooser gives such
// lights probability 0, so a wrong 0 is bias), and united bounds must contain what they unite.
#include "core/light_bounds.h"

#include <gtest/gtest.h>

#include <random>

#include "core/front_face.h"

namespace tray {
namespace {

struct Random {
  std::mt19937 gen{7};
  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(gen); }
  Vec3 point(float r) { return {uniform(-r, r), uniform(-r, r), uniform(-r, r)}; }
  Vec3 direction() {
    for (;;) {
      Vec3 v = point(1);
      if (lengthSquared(v) > 1e-2f && lengthSquared(v) <= 1) return normalize(v);
    }
  }
};

struct Triangle {
  Vec3 a, b, c;
  bool twoSided;
  Vec3 normal() const { return normalize(cross(b - a, c - a)); }
  LightBounds bounds() const {
    Bounds3 box;
    box.extend(a), box.extend(b), box.extend(c);
    return LightBounds::finite(box, normal(), 1.0f, 1.0f, 0.0f, twoSided);
  }
};

Triangle randomTriangle(Random& r) {
  const Vec3 c = r.point(2);
  return {c + r.point(0.5f), c + r.point(0.5f), c + r.point(0.5f), r.uniform(0, 1) < 0.3f};
}

LightSampleContext randomReceiver(Random& r) {
  return {r.point(3), r.direction(), false, r.uniform(0, 1) < 0.3f};
}

/// Whether some point of t (of 400 spread over it) emits towards ctx.p from above its horizon.
bool canLight(const Triangle& t, const LightSampleContext& ctx) {
  for (int i = 0; i < 20; ++i)
    for (int j = 0; i + j < 20; ++j) {
      const float u = (float(i) + 0.3f) / 20, v = (float(j) + 0.3f) / 20;
      const Vec3 q = t.a + u * (t.b - t.a) + v * (t.c - t.a);
      const Vec3 toLight = normalize(q - ctx.p);
      if (!emitsToward(t.normal(), -toLight, t.twoSided)) continue;
      if (ctx.belowMatters || dot(ctx.n, toLight) > 0) return true;
    }
  return false;
}

TEST(LightBounds, ATriangleHasImportanceZeroOnlyWhereItCannotLightTheReceiver) {
  Random r;
  int zeros = 0, positives = 0;
  for (int i = 0; i < 4000; ++i) {
    const Triangle t = randomTriangle(r);
    const LightSampleContext ctx = randomReceiver(r);
    const float importance = t.bounds().importance(ctx);
    if (importance > 0) {
      ++positives;
      continue;
    }
    ++zeros;
    EXPECT_FALSE(canLight(t, ctx)) << "receiver " << i;
  }
  // Both outcomes occur often: the test looks at culling, not at a corner of it.
  EXPECT_GT(zeros, 1000);
  EXPECT_GT(positives, 1000);
}

TEST(LightBounds, UnitedBoundsHoldBothAndAreZeroOnlyWhereNeitherCanLight) {
  // Not "only where both bounds are 0": a child's bounding sphere may reach outside its
  // parent's, but the light itself may not.
  Random r;
  int zeros = 0;
  for (int i = 0; i < 2000; ++i) {
    const Triangle ta = randomTriangle(r), tb = randomTriangle(r);
    const LightBounds a = ta.bounds(), b = tb.bounds();
    const LightBounds u = unite(a, b);
    EXPECT_FLOAT_EQ(u.phi, 2.0f);
    for (const LightBounds* x : {&a, &b}) {
      EXPECT_LE(u.box.lo.x, x->box.lo.x);
      EXPECT_GE(u.box.hi.z, x->box.hi.z);
      EXPECT_GE(dot(u.w, x->w), u.cosTheta_o - 1e-5f) << "cone " << i;
    }
    for (int k = 0; k < 8; ++k) {
      const LightSampleContext ctx = randomReceiver(r);
      if (u.importance(ctx) > 0) continue;
      ++zeros;
      EXPECT_FALSE(canLight(ta, ctx)) << i;
      EXPECT_FALSE(canLight(tb, ctx)) << i;
    }
  }
  EXPECT_GT(zeros, 500);
}

TEST(LightBounds, ASunBehindTheReceiverIsCulledUnlessLightFromBelowMatters) {
  const LightBounds sun = LightBounds::directional(normalize(Vec3(0, 1, 1)), 3.0f);
  LightSampleContext up{{0, 0, 0}, {0, 1, 0}};
  EXPECT_NEAR(sun.importance(up), 3.0f / std::sqrt(2.0f), 1e-5f);
  LightSampleContext down{{0, 0, 0}, {0, -1, 0}};
  EXPECT_EQ(sun.importance(down), 0.0f);
  down.belowMatters = true;
  EXPECT_NEAR(sun.importance(down), 3.0f / std::sqrt(2.0f), 1e-5f);
  EXPECT_NEAR(LightBounds::ambient(0.5f).importance(down), kPi * 0.5f, 1e-6f);
}

TEST(LightBounds, ASpotIsCulledOutsideItsOuterConeAndAPointNowhere) {
  Bounds3 at;
  at.extend(Vec3(0, 2, 0));
  const LightBounds spot = LightBounds::finite(at, {0, -1, 0}, 5.0f, std::cos(0.5f), 1.0f, false);
  const LightBounds point = LightBounds::finite(at, {0, 0, 1}, 5.0f, -1.0f, 0.0f, false);
  const LightSampleContext below{{0.5f, 0, 0}, {0, 1, 0}};   // 0.24 rad off the axis
  const LightSampleContext aside{{2.0f, 0, 0}, {0, 1, 0}};   // 0.79 rad off the axis
  EXPECT_NEAR(spot.importance(below), 5.0f * (2 / std::sqrt(4.25f)) / 4.25f, 1e-4f);
  EXPECT_EQ(spot.importance(aside), 0.0f);
  EXPECT_GT(point.importance(aside), 0.0f);
}

TEST(LightBounds, ANearClusterIsSeenFromItsCentreDownToHalfItsRadius) {
  // A flat box 2 x 0.2 x 2 emitting up (r^2 = 2.01), a receiver above its centre facing it:
  // every orientation term is 1 and the importance is phi / max(d^2, r^2 / 4) (Cycles' light
  // tree). pbrt-v4's clamp to the whole radius gave phi / 2.01 at both points.
  Bounds3 box;
  box.extend(Vec3(-1, -0.1f, -1));
  box.extend(Vec3(1, 0.1f, 1));
  const LightBounds b = LightBounds::finite(box, {0, 1, 0}, 3.0f, 1.0f, 0.0f, false);
  const LightSampleContext at09{{0, 0.9f, 0}, {0, -1, 0}}, at05{{0, 0.5f, 0}, {0, -1, 0}};
  EXPECT_NEAR(b.importance(at09), 3.0f / 0.81f, 1e-4f);
  EXPECT_NEAR(b.importance(at05), 3.0f / (2.01f / 4), 1e-4f);
  const LightSampleContext inside{{0.5f, 0, 0.5f}, {0, 1, 0}};  // inside: phi / r^2
  EXPECT_NEAR(b.importance(inside), 3.0f / 2.01f, 1e-4f);
}

TEST(LightBounds, ANearBoxWhollyBehindItsEmissionOrBelowTheHorizonIsCulled) {
  // A flat box 2 x 0.1 x 2 and a receiver just above one end of it: seen from there the box
  // spans more than a hemisphere, so no cone bounds it; still, lamps facing down that all lie
  // below the receiver cannot light it, nor can lamps facing up below its horizon.
  Bounds3 box;
  box.extend(Vec3(-1, 0, -1));
  box.extend(Vec3(1, 0.1f, 1));
  const LightBounds down = LightBounds::finite(box, {0, -1, 0}, 3.0f, 1.0f, 0.0f, false);
  const LightBounds up = LightBounds::finite(box, {0, 1, 0}, 3.0f, 1.0f, 0.0f, false);
  const LightSampleContext above{{0.9f, 0.12f, 0}, {0, 1, 0}}, below{{0.9f, -0.02f, 0}, {0, 1, 0}};
  const LightSampleContext facingDown{{0.9f, 0.12f, 0}, {0, -1, 0}};
  EXPECT_EQ(down.importance(above), 0.0f);
  EXPECT_EQ(up.importance(above), 0.0f);  // below the horizon
  EXPECT_GT(up.importance(facingDown), 0.0f);
  EXPECT_GT(down.importance(below), 0.0f);
  LightSampleContext transmits = above;
  transmits.belowMatters = true;
  EXPECT_GT(up.importance(transmits), 0.0f);
}

}  // namespace
}  // namespace tray

#include "core/light_bounds.h"

#include <algorithm>
#include <cmath>

namespace tray {

namespace {

/// An angle in [0, pi] by its cosine and sine.
struct Angle {
  float cos = 1, sin = 0;
};

Angle fromCos(float c) {
  c = std::clamp(c, -1.0f, 1.0f);
  return {c, std::sqrt(std::max(0.0f, 1.0f - c * c))};
}

/// max(0, a - b), by cosine and sine, without trigonometric calls.
Angle minusClamped(Angle a, Angle b) {
  if (a.cos >= b.cos) return {};  // a <= b
  return {a.cos * b.cos + a.sin * b.sin, a.sin * b.cos - a.cos * b.sin};
}

bool inside(const Bounds3& b, const Vec3& p) {
  return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z &&
         p.z <= b.hi.z;
}

/// The half-angle of a cone from p about `axis` (unit, towards the box's centre) that holds
/// the box: it holds the 8 corners, hence (a cone narrower than a hemisphere being convex)
/// the box. A half-angle of pi/2 or more: the whole sphere.
Angle coneAroundCorners(const Bounds3& b, const Vec3& p, const Vec3& axis) {
  float cosMin = 1;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner(i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z);
    const Vec3 v = corner - p;
    const float len = length(v);
    if (!(len > 0)) return {-1, 0};
    cosMin = std::min(cosMin, dot(v, axis) / len);
  }
  return cosMin > 0 ? fromCos(cosMin) : Angle{-1, 0};
}

/// The smallest dot(a, x) over the box.
float leastDot(const Bounds3& b, const Vec3& a) {
  return (a.x > 0 ? a.x * b.lo.x : a.x * b.hi.x) + (a.y > 0 ? a.y * b.lo.y : a.y * b.hi.y) +
         (a.z > 0 ? a.z * b.lo.z : a.z * b.hi.z);
}

/// Whether the whole box lies where its lights cannot reach p: behind the emission half-space
/// (a light at x reaches p only within theta_o + theta_e of w; when that is at most pi/2, only
/// if dot(w, p - x) >= 0) or below the receiver's horizon.
bool wholeBoxCulled(const LightBounds& l, const LightSampleContext& ctx) {
  const float sinE = std::sqrt(std::max(0.0f, 1.0f - l.cosTheta_e * l.cosTheta_e));
  if (!l.twoSided && l.cosTheta_o >= 0 && l.cosTheta_e >= 0 &&
      l.cosTheta_o * l.cosTheta_e - l.sinTheta_o * sinE >= 0 &&
      leastDot(l.box, l.w) > dot(l.w, ctx.p))
    return true;
  return !ctx.belowMatters && leastDot(l.box, -ctx.n) > -dot(ctx.n, ctx.p);
}

float finiteImportance(const LightBounds& l, const LightSampleContext& ctx) {
  const Vec3 pc = l.box.center();
  const float r2 = 0.25f * lengthSquared(l.box.diagonal());
  const Vec3 d = ctx.p - pc;
  const float d2 = lengthSquared(d);
  if (!(d2 > 0) || (r2 > 0 && inside(l.box, ctx.p))) return r2 > 0 ? l.phi / r2 : 0.0f;
  const Vec3 wi = d / std::sqrt(d2);  // from the light towards the receiver
  // A cone from the receiver holding the box: from its bounding sphere when outside it, else
  // from its corners (which keeps the orientation terms near big boxes). Inside the box, or
  // where the cone is wider than a hemisphere, every direction is possible: only the
  // distance is known.
  const Angle bound = d2 > r2 ? fromCos(std::sqrt(std::max(0.0f, 1.0f - r2 / d2)))
                              : coneAroundCorners(l.box, ctx.p, -wi);
  // The distance to the centre, at least half the bounding sphere's radius (Cycles' light
  // tree, after Conty Estevez & Kulla 2018). pbrt-v4 12.6.3 clamps to the whole radius: every
  // receiver within a radius of the centre then sees the cluster as if from its sphere, and a
  // cluster holding the receiver's near lamp loses to a far one of more power (issue 37: the
  // many-light scenes' chooser efficiency 0.28 -> 0.41, squared error x CPU time 1.8-3x
  // lower; docs/bench/light-bvh-importance-2026-12-07.md). Inside the box it stays phi / r^2.
  const float dist2 = std::max(d2, 0.25f * r2);
  if (bound.cos < 0) return wholeBoxCulled(l, ctx) ? 0.0f : l.phi / dist2;
  const float cosW = dot(l.w, wi);
  const Angle toNormals = fromCos(l.twoSided ? std::fabs(cosW) : cosW);
  // The smallest angle between an emission normal and a direction to the receiver.
  const Angle emit = minusClamped(minusClamped(toNormals, {l.cosTheta_o, l.sinTheta_o}), bound);
  if (emit.cos < l.cosTheta_e) return 0.0f;
  // The smallest angle between the receiver's normal and a direction to the box.
  const float cosI = -dot(wi, ctx.n);
  const Angle incident = minusClamped(fromCos(ctx.belowMatters ? std::fabs(cosI) : cosI), bound);
  if (!(incident.cos > 0)) return 0.0f;
  return l.phi * std::max(emit.cos, 0.0f) * incident.cos / dist2;
}

}  // namespace

float LightBounds::importance(const LightSampleContext& ctx) const {
  float v = 0;
  switch (kind) {
    case Kind::kFinite:
      v = finiteImportance(*this, ctx);
      break;
    case Kind::kDirectional: {
      const float c = dot(ctx.n, w);
      v = phi * (ctx.belowMatters ? std::fabs(c) : std::max(c, 0.0f));
      break;
    }
    case Kind::kAmbient:
      v = phi;
      break;
  }
  return std::isfinite(v) && v > 0 ? v : 0.0f;
}

namespace {

/// The smallest cone holding cones (wa, theta_a) and (wb, theta_b) (Conty Estevez & Kulla,
/// Algorithm 1): axis and cosine of the half-angle.
void uniteCones(const Vec3& wa, float cosA, const Vec3& wb, float cosB, Vec3& w, float& cosO) {
  const float thetaA = std::acos(std::clamp(cosA, -1.0f, 1.0f));
  const float thetaB = std::acos(std::clamp(cosB, -1.0f, 1.0f));
  const float thetaD = std::acos(std::clamp(dot(wa, wb), -1.0f, 1.0f));
  if (std::min(thetaD + thetaB, kPi) <= thetaA) return void((w = wa, cosO = cosA));
  if (std::min(thetaD + thetaA, kPi) <= thetaB) return void((w = wb, cosO = cosB));
  const float thetaO = 0.5f * (thetaA + thetaD + thetaB);
  const Vec3 axis = cross(wa, wb);
  w = wa;
  cosO = -1;  // the whole sphere
  if (thetaO >= kPi || !(lengthSquared(axis) > 1e-12f)) return;
  // Turn wa towards wb by thetaO - thetaA (Rodrigues; the axis is orthogonal to wa).
  const float r = thetaO - thetaA;
  const Vec3 k = normalize(axis);
  w = normalize(wa * std::cos(r) + cross(k, wa) * std::sin(r));
  cosO = std::cos(thetaO);
}

}  // namespace

LightBounds unite(const LightBounds& a, const LightBounds& b) {
  if (!(a.phi > 0)) return b;
  if (!(b.phi > 0)) return a;
  LightBounds u = a;
  u.box.extend(b.box);
  u.phi = a.phi + b.phi;
  uniteCones(a.w, a.cosTheta_o, b.w, b.cosTheta_o, u.w, u.cosTheta_o);
  u.sinTheta_o = fromCos(u.cosTheta_o).sin;
  u.cosTheta_e = std::min(a.cosTheta_e, b.cosTheta_e);
  u.twoSided = a.twoSided || b.twoSided;
  return u;
}

}  // namespace tray

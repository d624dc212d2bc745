#include "core/light_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

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

int g_variant = [] {
  const char* e = std::getenv("TRAY_LBVH_VARIANT");
  return e ? std::atoi(e) : 0;
}();
float g_f = [] {
  const char* e = std::getenv("TRAY_LBVH_F");
  return e ? float(std::atof(e)) : 1.0f;
}();
float g_floor = [] {
  const char* e = std::getenv("TRAY_LBVH_FLOOR");
  return e ? float(std::atof(e)) : 1e-3f;
}();
int variant() { return g_variant; }

/// The box of the points of b with dot(a, x) <= c (a bound; empty when there are none).
Bounds3 clipBelow(const Bounds3& b, const Vec3& a, float c) {
  const float av[3] = {a.x, a.y, a.z};
  float lo[3] = {b.lo.x, b.lo.y, b.lo.z}, hi[3] = {b.hi.x, b.hi.y, b.hi.z};
  float least[3], minDot = 0;
  for (int k = 0; k < 3; ++k) minDot += least[k] = av[k] > 0 ? av[k] * lo[k] : av[k] * hi[k];
  if (minDot > c) return Bounds3();
  for (int k = 0; k < 3; ++k) {
    const float rest = minDot - least[k];
    if (av[k] > 0) hi[k] = std::min(hi[k], std::max(lo[k], (c - rest) / av[k]));
    if (av[k] < 0) lo[k] = std::max(lo[k], std::min(hi[k], (c - rest) / av[k]));
  }
  Bounds3 out;
  out.lo = Vec3(lo[0], lo[1], lo[2]);
  out.hi = Vec3(hi[0], hi[1], hi[2]);
  return out;
}

void finiteImportance(const LightBounds& l, const LightSampleContext& ctx, float& hi, float& lo) {
  hi = lo = 0;
  const int v = variant();
  Bounds3 box = l.box;
  if ((v & 4) && !((v & 128) && inside(box, ctx.p))) {
    const float sinE = std::sqrt(std::max(0.0f, 1.0f - l.cosTheta_e * l.cosTheta_e));
    const float cosW = l.cosTheta_o * l.cosTheta_e - l.sinTheta_o * sinE;
    if (!l.twoSided && l.cosTheta_o >= 0 && l.cosTheta_e >= 0 && cosW >= 0) box = clipBelow(box, l.w, dot(l.w, ctx.p));
    if (!ctx.belowMatters && !box.empty()) box = clipBelow(box, -ctx.n, dot(-ctx.n, ctx.p));
    if (box.empty()) return;
  }
  float phi = l.phi;
  if (v & 64) {
    const Vec3 a = l.box.diagonal(), b = box.diagonal();
    float frac = 1;
    if (a.x > 0) frac *= b.x / a.x;
    if (a.y > 0) frac *= b.y / a.y;
    if (a.z > 0) frac *= b.z / a.z;
    const float floorF = g_floor;
    phi *= std::max(frac, floorF);
  }
  const Vec3 pc = box.center();
  const float r2 = 0.25f * lengthSquared(box.diagonal());
  const float f = g_f;
  const float rc2 = (v & 2) ? r2 * f : r2;
  const Vec3 d = ctx.p - pc;
  const float d2 = lengthSquared(d);
  if (!(d2 > 0) || (r2 > 0 && inside(box, ctx.p))) {
    hi = r2 > 0 ? phi / ((v & 16) ? r2 : rc2) : 0.0f;
    return;
  }
  const Vec3 wi = d / std::sqrt(d2);  // from the light towards the receiver
  const Angle bound = ((v & 8) == 0 && d2 > r2) ? fromCos(std::sqrt(std::max(0.0f, 1.0f - r2 / d2)))
                              : coneAroundCorners(box, ctx.p, -wi);
  if (bound.cos < 0) {
    hi = phi / std::max(d2, rc2);
    return;
  }
  const float cosW = dot(l.w, wi);
  const Angle toNormals = fromCos(l.twoSided ? std::fabs(cosW) : cosW);
  // The smallest angle between an emission normal and a direction to the receiver.
  const Angle emit = minusClamped(minusClamped(toNormals, {l.cosTheta_o, l.sinTheta_o}), bound);
  if (emit.cos < l.cosTheta_e) return;
  // The smallest angle between the receiver's normal and a direction to the box.
  const float cosI = -dot(wi, ctx.n);
  const Angle i0 = fromCos(ctx.belowMatters ? std::fabs(cosI) : cosI);
  const Angle incident = minusClamped(i0, bound);
  if (!(incident.cos > 0)) return;
  hi = phi * std::max(emit.cos, 0.0f) * incident.cos / std::max(d2, rc2);
  // The least: the largest angles (theta + theta_o + theta_u, theta_i + theta_u; Cycles).
  auto plus = [](Angle a, Angle b) {
    return Angle{a.cos * b.cos - a.sin * b.sin, a.sin * b.cos + a.cos * b.sin};
  };
  const Angle iMax = plus(i0, bound);
  const float thetaMax = std::acos(std::clamp(toNormals.cos, -1.f, 1.f)) + std::acos(l.cosTheta_o) +
                         std::acos(bound.cos);
  const float cosE = thetaMax < kPi ? std::cos(thetaMax) : -1.0f;
  if (iMax.cos > 0 && iMax.sin >= 0 && cosE >= l.cosTheta_e && cosE > 0)
    lo = phi * cosE * iMax.cos / std::max(d2, rc2);
}

}  // namespace

float LightBounds::importance(const LightSampleContext& ctx) const {
  float v = 0;
  switch (kind) {
    case Kind::kFinite: {
      float lo;
      finiteImportance(*this, ctx, v, lo);
      break;
    }
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

void LightBounds::importanceRange(const LightSampleContext& ctx, float& hi, float& lo) const {
  if (kind != Kind::kFinite) {
    hi = lo = importance(ctx);
    return;
  }
  finiteImportance(*this, ctx, hi, lo);
  if (!(std::isfinite(hi) && hi > 0)) hi = 0;
  if (!(std::isfinite(lo) && lo > 0)) lo = 0;
}

int lightBvhVariant() { return variant(); }
void setLightBvhExperiment(int v, float f, float fl) { g_variant = v, g_f = f, g_floor = fl; }

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

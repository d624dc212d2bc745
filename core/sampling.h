#pragma once
// Warping functions: uniform numbers in [0,1)^2 to directions and points, each with its pdf.
// Derivations in pbrt-v4 (Pharr, Jakob, Humphreys 2023), sections A.5 and 4.3.
#include <cmath>

#include "core/math.h"

namespace tray {

/// sin(pi/4 t) and cos(pi/4 t) for t in [-1, 1], as polynomials in t: within 1.7 ulps of the
/// exact values over the whole range (libm's sinf of the rounded angle: 1.9). Why not libm: the
/// SIMD shading stages (integrators/shading_simd-inl.h) must draw the same directions as this
/// scalar code bit for bit, and glibc's sinf and cosf evaluate in double, lane by lane; these
/// few multiplies and adds run the same in every lane. Coefficients: least squares on 20000
/// Chebyshev nodes in double (sin relative, cos absolute), rounded to float; Horner's rule
/// without fused multiply-adds. tests/core/sampling_test.cpp checks the bound.
inline constexpr float kSinQuarterPi[5] = {0.7853981852531433f, -0.08074551075696945f,
                                           0.002490393118932843f, -3.6572346289176494e-05f,
                                           3.089738527251029e-07f};
inline constexpr float kCosQuarterPi[5] = {1.0f, -0.3084251284599304f, 0.015854325145483017f,
                                           -0.0003259385994169861f, 3.529804189383867e-06f};
inline void sinCosQuarterPi(float t, float& sine, float& cosine) {
  const float t2 = t * t;
  const float* s = kSinQuarterPi;
  const float* c = kCosQuarterPi;
  sine = ((((s[4] * t2 + s[3]) * t2 + s[2]) * t2 + s[1]) * t2 + s[0]) * t;
  cosine = (((c[4] * t2 + c[3]) * t2 + c[2]) * t2 + c[1]) * t2 + c[0];
}

/// (cos, sin) of 2 pi u for u in [0, 1]: the nearest quarter turn k = round(4u), then the
/// rest, pi/4 t with t = 2 (4u - k) in [-1, 1] (both steps exact), by sinCosQuarterPi.
inline Vec2 cosSinTwoPi(float u) {
  const float k = std::floor(4.0f * u + 0.5f);
  float s, c;
  sinCosQuarterPi(2.0f * (4.0f * u - k), s, c);
  // Turned by k quarter turns: (c, s), (-s, c), (-c, -s), (s, -c).
  const int quarter = int(k) & 3;
  const float x = quarter & 1 ? s : c, y = quarter & 1 ? c : s;
  return {quarter == 1 || quarter == 2 ? -x : x, quarter >= 2 ? -y : y};
}

/// Uniform point on the unit disk, Shirley & Chiu's concentric map (pbrt-v4 A.5.1): keeps
/// strata compact, so stratified input stays stratified.
inline Vec2 sampleUniformDiskConcentric(Vec2 u) {
  float ox = 2.0f * u.x - 1.0f, oy = 2.0f * u.y - 1.0f;
  if (ox == 0 && oy == 0) return {0, 0};
  // Selects, not branches: which wedge applies is a coin flip per sample, a branch on it is
  // mispredicted half the time. The x wedge's angle is pi/4 (oy/ox); the y wedge's is
  // pi/2 - pi/4 (ox/oy), whose cosine and sine are the sine and cosine of pi/4 (ox/oy).
  const bool xWedge = std::fabs(ox) > std::fabs(oy);
  const float r = xWedge ? ox : oy;
  float s, c;
  sinCosQuarterPi((xWedge ? oy : ox) / r, s, c);
  return {r * (xWedge ? c : s), r * (xWedge ? s : c)};
}

/// Uniform point on the unit disk in polar form (used by visible-normal sampling).
inline Vec2 sampleUniformDiskPolar(Vec2 u) {
  const float r = std::sqrt(u.x);
  const Vec2 cs = cosSinTwoPi(u.y);
  return {r * cs.x, r * cs.y};
}

/// Cosine-weighted direction about +z (Malley's method); pdf = cos(theta) / pi, always > 0.
/// The concentric map sends u.x == 0 or u.y == 0 to the disk's rim, the horizon, where the pdf
/// is 0 and every caller must drop the sample: one sample in 2^24 per coordinate of 24-bit
/// uniforms came back black (the white furnace's lost sample). z is kept at least 2^-11 (about
/// 0.03 degrees above the horizon) instead; the rim has measure zero, so nothing is biased.
inline Vec3 sampleCosineHemisphere(Vec2 u) {
  Vec2 d = sampleUniformDiskConcentric(u);
  // The same arithmetic as an unclamped map inside (images stay bit for bit), floored at
  // 2^-22 under the square root: z >= 2^-11.
  float z = std::sqrt(std::max(0x1p-22f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
inline float cosineHemispherePdf(float cosTheta) {
  return std::max(0.0f, cosTheta) / kPi;
}

/// Uniform direction on the unit sphere; pdf = 1 / (4 pi).
inline Vec3 sampleUniformSphere(Vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);

/// Uniform direction in the cone of half-angle acos(cosMax) about +z; pdf = 1 / (2 pi (1 -
/// cosMax)). For tiny cones 1 - cosMax cancels: pass it directly as oneMinusCosMax.
inline Vec3 sampleUniformCone(Vec2 u, float oneMinusCosMax) {
  float oneMinusCos = u.x * oneMinusCosMax;
  float cosTheta = 1.0f - oneMinusCos;
  float sinTheta = std::sqrt(std::max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
  float phi = 2.0f * kPi * u.y;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}
inline float uniformConePdf(float oneMinusCosMax) {
  return 1.0f / (2.0f * kPi * oneMinusCosMax);
}

/// Uniform barycentrics (b0, b1, b2) on a triangle (Heitz 2019, "A Low-Distortion Map Between
/// Triangle and Square"); pdf = 1 / area.
inline Vec3 sampleUniformTriangle(Vec2 u) {
  // Selects rather than a branch on the coin flip u.x < u.y (same values).
  const bool lower = u.x < u.y;
  const float half = (lower ? u.x : u.y) / 2;
  const float b0 = lower ? half : u.x - half, b1 = lower ? u.y - half : half;
  return {b0, b1, 1.0f - b0 - b1};
}

/// Veach's power heuristic (beta = 2) for two strategies with nf and ng samples' pdfs.
inline float powerHeuristic(float pf, float pg) {
  if (std::isinf(pf)) return 1.0f;
  float f2 = pf * pf, g2 = pg * pg;
  return f2 + g2 > 0 ? f2 / (f2 + g2) : 0.0f;
}

/// A shading frame: local +z is the normal.
struct Frame {
  Vec3 t, b, n;
  static Frame fromNormal(const Vec3& n) {
    Frame f;
    f.n = n;
    orthonormalBasis(n, f.t, f.b);
    return f;
  }
  Vec3 toLocal(const Vec3& v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
  Vec3 toWorld(const Vec3& v) const { return v.x * t + v.y * b + v.z * n; }
};

}  // namespace tray

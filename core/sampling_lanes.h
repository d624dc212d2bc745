// Warping functions and MIS, written once over the lane type (core/lane_ops.h, docs/lanes.md):
// uniform numbers in [0,1)^2 to directions and points, each with its pdf, and the shading
// frame. Derivations in pbrt-v4 (Pharr, Jakob, Humphreys 2023), sections A.5 and 4.3. Scalar
// code includes core/sampling.h; a SIMD stage includes this file again in each target's pass
// with TRAY_LANES_SIMD defined.
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_SAMPLING_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_SAMPLING_LANES_SIMD_
#undef TRAY_CORE_SAMPLING_LANES_SIMD_
#else
#define TRAY_CORE_SAMPLING_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_SAMPLING_LANES_SCALAR_)
#define TRAY_CORE_SAMPLING_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// std::clamp(v, lo, hi) as libstdc++ writes it, std::min(std::max(v, lo), hi): a NaN v stays
/// NaN.
template <class F>
TRAY_LANE F clampOf(F v, F lo, F hi) {
  return minOf(maxOf(v, lo), hi);
}

/// sin(pi/4 t) and cos(pi/4 t) for t in [-1, 1], as polynomials in t: within 1.7 ulps of the
/// exact values over the whole range (libm's sinf of the rounded angle: 1.9). Why not libm:
/// glibc's sinf and cosf evaluate in double, lane by lane; these few multiplies and adds run
/// the same in every lane of either lane type. Coefficients: least squares on 20000 Chebyshev
/// nodes in double (sin relative, cos absolute), rounded to float; Horner's rule without fused
/// multiply-adds. tests/core/sampling_test.cpp checks the bound.
inline constexpr float kSinQuarterPi[5] = {0.7853981852531433f, -0.08074551075696945f,
                                           0.002490393118932843f, -3.6572346289176494e-05f,
                                           3.089738527251029e-07f};
inline constexpr float kCosQuarterPi[5] = {1.0f, -0.3084251284599304f, 0.015854325145483017f,
                                           -0.0003259385994169861f, 3.529804189383867e-06f};
template <class F>
TRAY_LANE void sinCosQuarterPi(F t, F& sine, F& cosine) {
  const F t2 = t * t;
  const auto s = [](int i) { return F(kSinQuarterPi[i]); };
  const auto c = [](int i) { return F(kCosQuarterPi[i]); };
  sine = ((((s(4) * t2 + s(3)) * t2 + s(2)) * t2 + s(1)) * t2 + s(0)) * t;
  cosine = (((c(4) * t2 + c(3)) * t2 + c(2)) * t2 + c(1)) * t2 + c(0);
}

/// (cos, sin) of 2 pi u for u in [0, 1]: the nearest quarter turn k = round(4u), then the
/// rest, pi/4 t with t = 2 (4u - k) in [-1, 1] (both steps exact), by sinCosQuarterPi.
template <class F>
TRAY_LANE Vec2Of<F> cosSinTwoPi(F u) {
  using I = IntOf<F>;
  using M = MaskOf<F>;
  const F k = floorOf(F(4.0f) * u + F(0.5f));
  F s, c;
  sinCosQuarterPi(F(2.0f) * (F(4.0f) * u - k), s, c);
  // Turned by k quarter turns: (c, s), (-s, c), (-c, -s), (s, -c).
  const I quarter = truncateToInt(k) & I(3);
  const M odd = (quarter & I(1)) == I(1);
  const M negX = quarter == I(1) || quarter == I(2);
  const M negY = quarter > I(1);
  const F x = select(odd, s, c), y = select(odd, c, s);
  return {select(negX, -x, x), select(negY, -y, y)};
}

/// atan(t) for t in [0, 1] as t P(t^2), within 1.9 ulps of the exact value over the range.
/// Coefficients: least squares (relative) on 20000 Chebyshev nodes in double, rounded to
/// float; Horner's rule without fused multiply-adds (as sinCosQuarterPi, and for its reason:
/// the same bits in every lane of either lane type). tests/core/sampling_test.cpp checks it.
inline constexpr float kAtanUnit[9] = {1.0f,
                                       -0.3333311975002289f,
                                       0.19993291795253754f,
                                       -0.14207743108272552f,
                                       0.10653974115848541f,
                                       -0.07527676224708557f,
                                       0.04292982071638107f,
                                       -0.016197500750422478f,
                                       0.0028786147013306618f};
/// atan2(y, x) in [-pi, pi]: the octant's ratio min/max in [0, 1] through kAtanUnit, then
/// pi/2 - r where |y| > |x|, pi - r where x < 0, and y's sign. 0 where x == y == 0.
template <class F>
TRAY_LANE F atan2Of(F y, F x) {
  const F ax = absOf(x), ay = absOf(y);
  const F hi = maxOf(ax, ay), lo = minOf(ax, ay);
  const F t = select(hi > F(0.0f), lo / hi, F(0.0f));
  const F t2 = t * t;
  F p = F(kAtanUnit[8]);
  for (int i = 7; i >= 0; --i) p = p * t2 + F(kAtanUnit[i]);
  F r = p * t;
  r = select(ay > ax, F(0.5f * kPi) - r, r);
  r = select(x < F(0.0f), F(kPi) - r, r);
  return copySignOf(r, y);
}

/// Uniform point on the unit disk, Shirley & Chiu's concentric map (pbrt-v4 A.5.1): keeps
/// strata compact, so stratified input stays stratified. Selects, not branches: which wedge
/// applies is a coin flip per sample. The x wedge's angle is pi/4 (oy/ox); the y wedge's is
/// pi/2 - pi/4 (ox/oy), whose cosine and sine are the sine and cosine of pi/4 (ox/oy).
template <class V2>
TRAY_LANE V2 sampleUniformDiskConcentric(const V2& u) {
  using F = decltype(V2::x);
  const F ox = F(2.0f) * u.x - F(1.0f), oy = F(2.0f) * u.y - F(1.0f);
  const auto center = ox == F(0.0f) && oy == F(0.0f);
  const auto xWedge = absOf(ox) > absOf(oy);
  const F r = select(xWedge, ox, oy);
  F s, c;
  sinCosQuarterPi(select(xWedge, oy, ox) / r, s, c);
  return {select(center, F(0.0f), r * select(xWedge, c, s)),
          select(center, F(0.0f), r * select(xWedge, s, c))};
}

/// Uniform point on the unit disk in polar form (used by visible-normal sampling).
template <class V2>
TRAY_LANE V2 sampleUniformDiskPolar(const V2& u) {
  using F = decltype(V2::x);
  const F r = sqrtOf(u.x);
  const V2 cs = cosSinTwoPi(u.y);
  return {r * cs.x, r * cs.y};
}

/// Cosine-weighted direction about +z (Malley's method); pdf = cos(theta) / pi, always > 0.
/// The concentric map sends u.x == 0 or u.y == 0 to the disk's rim, the horizon, where the pdf
/// is 0 and every caller must drop the sample: one sample in 2^24 per coordinate of 24-bit
/// uniforms came back black (the white furnace's lost sample). z is kept at least 2^-11 (about
/// 0.03 degrees above the horizon) instead; the rim has measure zero, so nothing is biased.
template <class V2>
TRAY_LANE Vec3Of<decltype(V2::x)> sampleCosineHemisphere(const V2& u) {
  using F = decltype(V2::x);
  const V2 d = sampleUniformDiskConcentric(u);
  // The same arithmetic as an unclamped map inside, floored at 2^-22 under the square root.
  const F z = sqrtOf(maxOf(F(0x1p-22f), F(1.0f) - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
template <class F>
TRAY_LANE F cosineHemispherePdf(F cosTheta) {
  return maxOf(F(0.0f), cosTheta) / F(kPi);
}

/// Uniform barycentrics (b0, b1, b2) on a triangle (Heitz 2019, "A Low-Distortion Map Between
/// Triangle and Square"); pdf = 1 / area. Selects rather than a branch on the coin flip.
template <class V2>
TRAY_LANE Vec3Of<decltype(V2::x)> sampleUniformTriangle(const V2& u) {
  using F = decltype(V2::x);
  const auto lower = u.x < u.y;
  const F half = select(lower, u.x, u.y) / F(2.0f);
  const F b0 = select(lower, half, u.x - half), b1 = select(lower, u.y - half, half);
  return {b0, b1, F(1.0f) - b0 - b1};
}

/// x in [0, 1) with density proportional to (1 - x) a + x b (a, b > 0): the inverse of its
/// cdf (a x + (b - a) x^2 / 2) / ((a + b) / 2), rationalised so that a == b needs no
/// special case (pbrt-v4 A.4.1; Heitz's remark there).
template <class F>
TRAY_LANE F sampleLinear(F u, F a, F b) {
  const F x = u * (a + b) / (a + sqrtOf((F(1.0f) - u) * (a * a) + u * (b * b)));
  return minOf(x, F(0x1.fffffep-1f));
}

/// Bilinear weights at the corners of [0,1]^2: w00 at (0, 0), w10 at (1, 0), w01 at (0, 1),
/// w11 at (1, 1).
template <class F>
struct BilinearOf {
  F w00, w10, w01, w11;
};
/// A point of [0,1)^2 with density bilinearPdf: y from its marginal, then x given y (pbrt-v4
/// A.4.3).
template <class V2>
TRAY_LANE V2 sampleBilinear(const V2& u, const BilinearOf<decltype(V2::x)>& w) {
  using F = decltype(V2::x);
  const F y = sampleLinear(u.y, w.w00 + w.w10, w.w01 + w.w11);
  const F x =
      sampleLinear(u.x, (F(1.0f) - y) * w.w00 + y * w.w01, (F(1.0f) - y) * w.w10 + y * w.w11);
  return {x, y};
}
template <class V2>
TRAY_LANE decltype(V2::x) bilinearPdf(const V2& p, const BilinearOf<decltype(V2::x)>& w) {
  using F = decltype(V2::x);
  const F x1 = F(1.0f) - p.x, y1 = F(1.0f) - p.y;
  return F(4.0f) * (x1 * y1 * w.w00 + p.x * y1 * w.w10 + x1 * p.y * w.w01 + p.x * p.y * w.w11) /
         (w.w00 + w.w10 + w.w01 + w.w11);
}

/// Veach's power heuristic (beta = 2) for two strategies with one sample each: 1 where pf is
/// infinite (a delta strategy), 0 where neither has density.
template <class F>
TRAY_LANE F powerHeuristic(F pf, F pg) {
  const F f2 = pf * pf, g2 = pg * pg;
  const F sum = f2 + g2;
  return select(isInfOf(pf), F(1.0f), select(sum > F(0.0f), f2 / sum, F(0.0f)));
}

/// Orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis,
/// Revisited").
template <class V3>
TRAY_LANE void orthonormalBasis(const V3& n, V3& t, V3& b) {
  using F = decltype(V3::x);
  const F sign = copySignOf(F(1.0f), n.z);
  const F a = F(-1.0f) / (sign + n.z);
  const F bb = n.x * n.y * a;
  t = {F(1.0f) + sign * n.x * n.x * a, sign * bb, -sign * n.x};
  b = {bb, sign + n.y * n.y * a, -n.y};
}

/// A shading frame: local +z is the normal.
template <class V3>
struct FrameOf {
  V3 t, b, n;
  static FrameOf fromNormal(const V3& n) {
    FrameOf f;
    f.n = n;
    orthonormalBasis(n, f.t, f.b);
    return f;
  }
  V3 toLocal(const V3& v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
  V3 toWorld(const V3& v) const { return v.x * t + v.y * b + v.z * n; }
};

/// A cosine-weighted direction about the unit normal n, in world space, normalised (the frame's
/// rounding removed); its pdf is cosineHemispherePdf(dot(n, wi)).
template <class V3, class V2>
TRAY_LANE V3 sampleCosineAbout(const V3& n, const V2& u) {
  return normalize(FrameOf<V3>::fromNormal(n).toWorld(sampleCosineHemisphere(u)));
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

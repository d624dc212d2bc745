// The GGX (Trowbridge-Reitz) microfacet distribution with Smith height-correlated masking and
// sampling of visible normals, written once over the lane type (core/lane_ops.h,
// docs/lanes.md). Walter et al. 2007, "Microfacet Models for Refraction through Rough
// Surfaces"; Heitz 2014, "Understanding the Masking-Shadowing Function"; Heitz 2018, "Sampling
// the GGX Distribution of Visible Normals". Local frame: +z is the mean normal; alpha is
// GgxDistribution's (roughness^2, at least 1e-4). Scalar code includes materials/microfacet.h.
#ifdef TRAY_LANES_SIMD
#if defined(MATERIALS_MICROFACET_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef MATERIALS_MICROFACET_LANES_H_SIMD_
#undef MATERIALS_MICROFACET_LANES_H_SIMD_
#else
#define MATERIALS_MICROFACET_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(MATERIALS_MICROFACET_LANES_H_SCALAR_)
#define MATERIALS_MICROFACET_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// GGX's alpha is kept at least this (glTF's roughness 0.01): below it D overflows float.
inline constexpr float kGgxMinAlpha = 1e-4f;
/// Below this alpha the lobe is treated as a delta (mirror / perfect refraction): the GGX peak
/// would overflow float and no sampler could find it.
inline constexpr float kGgxSmoothAlpha = 1e-3f;
/// The alpha the distribution uses for a requested one (roughness^2, glTF's BRDF appendix).
template <class F>
TRAY_LANE F ggxAlpha(F alpha) {
  return maxOf(alpha, F(kGgxMinAlpha));
}

/// Microfacet normal density D(wm), projected-area normalised: integral D cos = 1.
/// Microfacets face the upper side only.
template <class V3, class F>
TRAY_LANE F ggxD(F alpha, const V3& wm) {
  const F cos2 = wm.z * wm.z;
  const F sin2 = maxOf(F(0.0f), F(1.0f) - cos2);
  const F a2 = alpha * alpha;
  const F e = cos2 + sin2 / a2;  // cos^2 (1 + tan^2 / a^2)
  return select(wm.z > F(0.0f), F(1.0f) / (F(kPi) * a2 * e * e), F(0.0f));
}
/// Smith's Lambda for GGX: infinite at grazing angles.
template <class V3, class F>
TRAY_LANE F ggxLambda(F alpha, const V3& w) {
  const F cos2 = w.z * w.z;
  const F tan2 = maxOf(F(0.0f), F(1.0f) - cos2) / cos2;
  const F l = (sqrtOf(F(1.0f) + alpha * alpha * tan2) - F(1.0f)) / F(2.0f);
  return select(cos2 <= F(0.0f), F(kInfinity), l);
}
/// Density of visible normals from direction w, G1(w) max(0, w.wm) D(wm) / cos(w), from D(wm)
/// and 1 + Lambda(w).
template <class V3, class F>
TRAY_LANE F ggxVisibleD(const V3& w, const V3& wm, F d, F onePlusLambda) {
  const F c = absOf(w.z);
  return select(c == F(0.0f), F(0.0f), F(1.0f) / onePlusLambda / c * d * absOf(dot(w, wm)));
}
/// Anisotropic GGX (Heitz 2014, eq. 85; Burley 2012 appendix B): alphaX along the local x
/// axis, alphaY along y. D(wm) = 1 / (pi ax ay (x^2/ax^2 + y^2/ay^2 + z^2)^2) for unit wm,
/// projected-area normalised like ggxD, which it equals for ax = ay up to rounding (the
/// isotropic functions stay the ones isotropic lobes call, so their floats are unchanged).
template <class V3, class F>
TRAY_LANE F ggxDAniso(F ax, F ay, const V3& wm) {
  const F x = wm.x / ax, y = wm.y / ay;
  const F e = x * x + y * y + wm.z * wm.z;
  return select(wm.z > F(0.0f), F(1.0f) / (F(kPi) * ax * ay * e * e), F(0.0f));
}
/// Smith's Lambda for anisotropic GGX (Heitz 2014, eq. 86): alpha projected on w's azimuth,
/// alpha_o^2 tan^2 = (x^2 ax^2 + y^2 ay^2) / z^2.
template <class V3, class F>
TRAY_LANE F ggxLambdaAniso(F ax, F ay, const V3& w) {
  const F cos2 = w.z * w.z;
  const F a2tan2 = (w.x * w.x * ax * ax + w.y * w.y * ay * ay) / cos2;
  const F l = (sqrtOf(F(1.0f) + a2tan2) - F(1.0f)) / F(2.0f);
  return select(cos2 <= F(0.0f), F(kInfinity), l);
}
/// Samples a visible microfacet normal of the anisotropic distribution from direction w
/// (Heitz 2018, listing 1, as in pbrt-v4 9.6.4): stretch w to the hemisphere configuration,
/// sample the projected disk, unstretch. For ax = ay the same operations as the isotropic
/// ggxSampleVisibleNormal below, which calls it.
template <class V3, class V2, class F>
TRAY_LANE V3 ggxSampleVisibleNormalAniso(F ax, F ay, const V3& w, const V2& u) {
  V3 wh = normalize(V3{ax * w.x, ay * w.y, w.z});
  wh = select(wh.z < F(0.0f), -wh, wh);
  const V3 up{F(0.0f), F(0.0f), F(1.0f)}, x{F(1.0f), F(0.0f), F(0.0f)};
  const V3 t1 = select(wh.z < F(0.99999f), normalize(cross(up, wh)), x);
  const V3 t2 = cross(wh, t1);
  V2 p = sampleUniformDiskPolar(u);
  const F h = sqrtOf(maxOf(F(0.0f), F(1.0f) - p.x * p.x));
  const F s = (F(1.0f) + wh.z) / F(2.0f);
  p.y = (F(1.0f) - s) * h + s * p.y;
  const F pz = sqrtOf(maxOf(F(0.0f), F(1.0f) - p.x * p.x - p.y * p.y));
  const V3 nh = p.x * t1 + p.y * t2 + pz * wh;
  return normalize(V3{ax * nh.x, ay * nh.y, maxOf(F(1e-6f), nh.z)});
}
/// Samples a visible microfacet normal from direction w (Heitz 2018, as in pbrt-v4 9.6.4).
template <class V3, class V2, class F>
TRAY_LANE V3 ggxSampleVisibleNormal(F alpha, const V3& w, const V2& u) {
  return ggxSampleVisibleNormalAniso(alpha, alpha, w, u);
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

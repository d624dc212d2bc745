// Fresnel reflectance, written once over the lane type (core/lane_ops.h, docs/lanes.md).
// Scalar code includes materials/fresnel.h; a SIMD stage includes this file again in each
// target's pass with TRAY_LANES_SIMD defined.
#ifdef TRAY_LANES_SIMD
#if defined(MATERIALS_FRESNEL_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef MATERIALS_FRESNEL_LANES_H_SIMD_
#undef MATERIALS_FRESNEL_LANES_H_SIMD_
#else
#define MATERIALS_FRESNEL_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(MATERIALS_FRESNEL_LANES_H_SCALAR_)
#define MATERIALS_FRESNEL_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// Exact unpolarised Fresnel reflectance of a dielectric interface (Born & Wolf; pbrt-v4
/// 9.3.2). cosI is the cosine with the normal on the incident side's +z; eta = n_t / n_i for
/// light arriving from +z. A negative cosI means arrival from the other side (eta inverted).
template <class F>
TRAY_LANE F fresnelDielectric(F cosI, F eta) {
  cosI = clampOf(cosI, F(-1.0f), F(1.0f));
  const auto below = cosI < F(0.0f);
  if (anyOf(below)) {  // rare: reflection off the inside of a dielectric
    eta = select(below, F(1.0f) / eta, eta);
    cosI = select(below, -cosI, cosI);
  }
  const F sin2I = F(1.0f) - cosI * cosI;
  const F sin2T = sin2I / (eta * eta);
  const F cosT = sqrtOf(maxOf(F(0.0f), F(1.0f) - sin2T));
  const F rParallel = (eta * cosI - cosT) / (eta * cosI + cosT);
  const F rPerpendicular = (cosI - eta * cosT) / (cosI + eta * cosT);
  const F r = (rParallel * rParallel + rPerpendicular * rPerpendicular) / F(2.0f);
  return select(sin2T >= F(1.0f), F(1.0f), r);  // total internal reflection
}

/// Schlick's approximation with a coloured F0: glTF's metal Fresnel (glTF 2.0 spec, appendix
/// B).
template <class V3, class F>
TRAY_LANE V3 fresnelSchlick(const V3& f0, F cosI) {
  const F m = clampOf(F(1.0f) - absOf(cosI), F(0.0f), F(1.0f));
  const F m5 = (m * m) * (m * m) * m;
  return f0 + (V3{F(1.0f), F(1.0f), F(1.0f)} - f0) * m5;
}

/// Refraction of w (pointing away from the surface) through normal n (+z side), eta = n_t /
/// n_i seen from +z (pbrt-v4 eq. 9.3 form). False (per lane) on total internal reflection;
/// etaRelative receives the eta actually used (inverted where w is below the surface). Where
/// false, wt and etaRelative are not meaningful.
template <class V3, class F>
TRAY_LANE MaskOf<F> refractDirection(const V3& w, V3 n, F eta, F& etaRelative, V3& wt) {
  F cosI = dot(n, w);
  const auto below = cosI < F(0.0f);
  if (anyOf(below)) {  // leaving the medium
    eta = select(below, F(1.0f) / eta, eta);
    cosI = select(below, -cosI, cosI);
    n = select(below, -n, n);
  }
  const F sin2I = maxOf(F(0.0f), F(1.0f) - cosI * cosI);
  const F sin2T = sin2I / (eta * eta);
  const auto refracts = !(sin2T >= F(1.0f));
  const F cosT = sqrtOf(F(1.0f) - sin2T);  // NaN where total internal reflection: not used
  wt = -w / eta + (cosI / eta - cosT) * n;
  etaRelative = eta;
  return refracts;
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

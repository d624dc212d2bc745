// Lambert's ideal diffuse reflection, f = albedo / pi on the side of wo, written once over the
// lane type (core/lane_ops.h, docs/lanes.md). Scalar code includes materials/lambert.h; a SIMD
// stage includes this file again in each target's pass.
#ifdef TRAY_LANES_SIMD
#if defined(MATERIALS_LAMBERT_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef MATERIALS_LAMBERT_LANES_H_SIMD_
#undef MATERIALS_LAMBERT_LANES_H_SIMD_
#else
#define MATERIALS_LAMBERT_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(MATERIALS_LAMBERT_LANES_H_SCALAR_)
#define MATERIALS_LAMBERT_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// f and pdf at cosines cosO, cosI (with any normal: the lobe reads nothing else).
template <class V3, class F>
TRAY_LANE V3 lambertEvalPdf(const V3& albedo, F cosO, F cosI, F& pdf) {
  const auto same = cosO * cosI > F(0.0f);
  pdf = select(same, cosineHemispherePdf(absOf(cosI)), F(0.0f));
  const V3 zero{F(0.0f), F(0.0f), F(0.0f)};
  return select(same, albedo * F(1.0f / kPi), zero);
}
/// A sample in the local frame: the cosine lobe on wo's side (wo's local z: woZ); its pdf is
/// positive and finite (sampleCosineHemisphere keeps z >= 2^-11), its f albedo / pi.
template <class V3>
struct LambertSampleOf {
  V3 wi, f;
  decltype(V3::x) pdf;
};
template <class V3, class V2, class F>
TRAY_LANE LambertSampleOf<V3> lambertSample(const V3& albedo, F woZ, const V2& u) {
  LambertSampleOf<V3> s;
  s.wi = sampleCosineHemisphere(u);
  s.wi.z = select(woZ < F(0.0f), -s.wi.z, s.wi.z);  // a select: the side is random per bounce
  s.pdf = cosineHemispherePdf(absOf(s.wi.z));
  s.f = albedo * F(1.0f / kPi);
  return s;
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

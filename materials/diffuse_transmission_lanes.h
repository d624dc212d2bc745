// KHR_materials_diffuse_transmission's diffuse lobe: Lambert reflection of albedo R on wo's
// side and Lambert transmission of albedo T on the other (the extension's README, "BTDF":
// diffuse_btdf = (1/pi) transmission colour, mirrored to the far hemisphere), written once over
// the lane type (core/lane_ops.h, docs/lanes.md). Scalar code includes
// materials/diffuse_transmission.h. The SIMD stages do not take it yet: Bsdf::isLambertOnly and
// isGgxMixture send such vertices to the scalar code.
#ifdef TRAY_LANES_SIMD
#if defined(MATERIALS_DIFFUSE_TRANSMISSION_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef MATERIALS_DIFFUSE_TRANSMISSION_LANES_H_SIMD_
#undef MATERIALS_DIFFUSE_TRANSMISSION_LANES_H_SIMD_
#else
#define MATERIALS_DIFFUSE_TRANSMISSION_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(MATERIALS_DIFFUSE_TRANSMISSION_LANES_H_SCALAR_)
#define MATERIALS_DIFFUSE_TRANSMISSION_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// The probability of sampling the transmitted side: the two albedos' shares (largest channel;
/// any positive choice is unbiased). 0 when nothing is transmitted, so that a lobe without
/// transmission samples exactly as Lambert does.
template <class V3>
TRAY_LANE decltype(V3::x) diffuseTransmissionProb(const V3& reflect, const V3& transmit) {
  using F = decltype(V3::x);
  const F r = maxOf(reflect.x, maxOf(reflect.y, reflect.z));
  const F t = maxOf(transmit.x, maxOf(transmit.y, transmit.z));
  const F sum = maxOf(r, F(0.0f)) + maxOf(t, F(0.0f));
  return select(sum > F(0.0f) && t > F(0.0f), t / sum, F(0.0f));
}

/// f and pdf at cosines cosO, cosI: reflect / pi on wo's side, transmit / pi on the other;
/// pdf = P(side) |cos_i| / pi with pTransmit = diffuseTransmissionProb.
template <class V3, class F>
TRAY_LANE V3 diffuseTransmissionEvalPdf(const V3& reflect, const V3& transmit, F pTransmit, F cosO,
                                        F cosI, F& pdf) {
  const auto same = cosO * cosI > F(0.0f);
  const auto other = cosO * cosI < F(0.0f);
  const F cosine = cosineHemispherePdf(absOf(cosI));
  pdf = select(same, (F(1.0f) - pTransmit) * cosine, select(other, pTransmit * cosine, F(0.0f)));
  const V3 zero{F(0.0f), F(0.0f), F(0.0f)};
  return select(same, reflect * F(1.0f / kPi), select(other, transmit * F(1.0f / kPi), zero));
}

/// A sample in the local frame: uc < pTransmit picks the far side, then the cosine lobe there
/// (u); f and pdf as diffuseTransmissionEvalPdf gives them.
template <class V3>
struct DiffuseTransmissionSampleOf {
  V3 wi, f;
  decltype(V3::x) pdf;
  MaskOf<decltype(V3::x)> transmitted;
};
template <class V3, class V2, class F>
TRAY_LANE DiffuseTransmissionSampleOf<V3> diffuseTransmissionSample(const V3& reflect,
                                                                    const V3& transmit, F pTransmit,
                                                                    F woZ, F uc, const V2& u) {
  DiffuseTransmissionSampleOf<V3> s;
  s.transmitted = uc < pTransmit;
  s.wi = sampleCosineHemisphere(u);
  // On wo's side, mirrored for a transmission.
  const auto below = (woZ < F(0.0f)) != s.transmitted;
  s.wi.z = select(below, -s.wi.z, s.wi.z);
  const F cosine = cosineHemispherePdf(absOf(s.wi.z));
  s.pdf = select(s.transmitted, pTransmit * cosine, (F(1.0f) - pTransmit) * cosine);
  s.f = select(s.transmitted, transmit * F(1.0f / kPi), reflect * F(1.0f / kPi));
  return s;
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

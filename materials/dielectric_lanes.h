// A smooth dielectric interface's sample (two delta lobes, exact Fresnel), written once over the
// lane type (core/lane_ops.h, docs/lanes.md). Scalar code includes materials/dielectric.h
// (DielectricLobe); the SIMD delta stage (integrators/delta_batch.cpp) includes this file again
// in each target's pass.
#ifdef TRAY_LANES_SIMD
#if defined(MATERIALS_DIELECTRIC_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef MATERIALS_DIELECTRIC_LANES_H_SIMD_
#undef MATERIALS_DIELECTRIC_LANES_H_SIMD_
#else
#define MATERIALS_DIELECTRIC_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(MATERIALS_DIELECTRIC_LANES_H_SCALAR_)
#define MATERIALS_DIELECTRIC_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include <type_traits>

#include "core/lane_ops.h"
#include "materials/fresnel_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// A delta lobe's sample in the local frame: direction, the delta's coefficient f and its
/// discrete probability pdf (no sample where pdf is 0), and for a refraction (`transmission`)
/// etaScale = (n_i / n_t)^2, else 1.
template <class V3>
struct DeltaSampleOf {
  V3 wi, f;
  decltype(V3::x) pdf, etaScale;
  MaskOf<decltype(V3::x)> transmission;
};

/// A Fresnel reflectance as a colour: a coloured one (V3) as it is, a plain one broadcast.
template <class V3, class R>
TRAY_LANE V3 reflectanceColour(const R& r) {
  if constexpr (std::is_same_v<R, V3>)
    return r;
  else
    return V3{r, r, r};
}

/// A smooth dielectric's sample given its reflectance at wo: R a lane float (exact Fresnel) or
/// a colour (KHR_materials_iridescence's film on glass), and the probability of choosing
/// reflection, R itself or, for a colour, its mean. Reflection: f = R / |cos_i|; refraction:
/// f = tint (1 - R) / |cos_t| / eta'^2 (radiance scales by 1 / eta'^2 across the boundary,
/// Veach 1997 ch. 5.2), probability 1 - choose. eta = n_t / n_i for light arriving from +z.
/// A refraction along the surface (cos_t 0) or total internal reflection gives none.
template <class V3, class F, class R>
TRAY_LANE DeltaSampleOf<V3> sampleSmoothDielectricWith(const V3& wo, F eta, const V3& tint, F uc,
                                                       const R& reflectance, F choose) {
  const auto reflects = uc < choose;
  DeltaSampleOf<V3> s;
  s.wi = V3{-wo.x, -wo.y, wo.z};
  s.f = reflectanceColour<V3>(reflectance / absOf(s.wi.z));
  s.pdf = choose;
  s.etaScale = F(1.0f);
  s.transmission = MaskOf<F>(false);
  if (anyOf(!reflects)) {  // for one float: only where it refracts
    F etap(1.0f);  // read below only where it refracts; set so no lane reads garbage
    V3 wt;
    const auto refracts = !reflects &&
                          refractDirection(wo, V3{F(0.0f), F(0.0f), F(1.0f)}, eta, etap, wt) &&
                          !(wt.z == F(0.0f));
    const F etap2 = etap * etap;
    const R transmittance = reflectanceColour<R>(F(1.0f)) - reflectance;
    s.wi = select(reflects, s.wi, wt);
    s.f = select(reflects, s.f, tint * reflectanceColour<V3>(transmittance / absOf(wt.z) / etap2));
    s.pdf = select(reflects, s.pdf, select(refracts, F(1.0f) - choose, F(0.0f)));
    s.etaScale = select(refracts, F(1.0f) / etap2, s.etaScale);
    s.transmission = refracts;
  }
  return s;
}

/// A smooth dielectric's sample (pbrt-v4 9.5.1): reflection where uc < R = Fresnel(cos_o), with
/// f = R / |cos_i| and probability R; else refraction, f = tint T / |cos_t| / eta'^2 with
/// probability T = 1 - R. tint: KHR_materials_transmission's base colour.
template <class V3, class F>
TRAY_LANE DeltaSampleOf<V3> sampleSmoothDielectric(const V3& wo, F eta, const V3& tint, F uc) {
  const F R = fresnelDielectric(wo.z, eta);
  return sampleSmoothDielectricWith(wo, eta, tint, uc, R, R);
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

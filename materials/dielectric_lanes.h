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

/// A smooth dielectric's sample (pbrt-v4 9.5.1): reflection where uc < R = Fresnel(cos_o), with
/// f = R / |cos_i| and probability R; else refraction, f = tint T / |cos_t| / eta'^2 with
/// probability T = 1 - R (radiance scales by 1 / eta'^2 across the boundary, Veach 1997 ch.
/// 5.2). eta = n_t / n_i for light arriving from +z; tint: KHR_materials_transmission's base
/// colour. A refraction along the surface (cos_t 0) or total internal reflection gives none.
template <class V3, class F>
TRAY_LANE DeltaSampleOf<V3> sampleSmoothDielectric(const V3& wo, F eta, const V3& tint, F uc) {
  const F R = fresnelDielectric(wo.z, eta), T = F(1.0f) - R;
  const auto reflects = uc < R;
  DeltaSampleOf<V3> s;
  s.wi = V3{-wo.x, -wo.y, wo.z};
  const F fr = R / absOf(s.wi.z);
  s.f = V3{fr, fr, fr};
  s.pdf = R;
  s.etaScale = F(1.0f);
  s.transmission = MaskOf<F>(false);
  if (anyOf(!reflects)) {  // for one float: only where it refracts
    F etap;
    V3 wt;
    const auto refracts = !reflects &&
                          refractDirection(wo, V3{F(0.0f), F(0.0f), F(1.0f)}, eta, etap, wt) &&
                          !(wt.z == F(0.0f));
    const F etap2 = etap * etap;
    s.wi = select(reflects, s.wi, wt);
    s.f = select(reflects, s.f, tint * (T / absOf(wt.z) / etap2));
    s.pdf = select(reflects, s.pdf, select(refracts, T, F(0.0f)));
    s.etaScale = select(refracts, F(1.0f) / etap2, s.etaScale);
    s.transmission = refracts;
  }
  return s;
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

// Microfacet reflection, f = D G F / (4 |cos_o cos_i|) (Walter et al. 2007, eq. 20), sampled
// through visible normals: the terms eval and pdf share, and the sampled direction, written
// once over the lane type (core/lane_ops.h, docs/lanes.md). Scalar code includes
// materials/ggx_reflection.h (GgxReflectionLobe, which adds the Fresnel factor and the delta
// limit); a SIMD stage includes this file again in each target's pass.
#ifdef TRAY_LANES_SIMD
#if defined(MATERIALS_GGX_REFLECTION_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef MATERIALS_GGX_REFLECTION_LANES_H_SIMD_
#undef MATERIALS_GGX_REFLECTION_LANES_H_SIMD_
#else
#define MATERIALS_GGX_REFLECTION_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(MATERIALS_GGX_REFLECTION_LANES_H_SCALAR_)
#define MATERIALS_GGX_REFLECTION_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "materials/microfacet_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// What eval and pdf share at one (wo, wi), computed once: the half vector, D and Lambda(wo).
/// They depend on alpha alone, so two lobes of one roughness (a mixture's metal and coat)
/// share them and differ only in the Fresnel factor.
template <class F>
struct GgxTermsOf {
  F cosOM;            ///< wo . wm, Fresnel's cosine (0 where not valid)
  F scale;            ///< D G / (4 |cos_o cos_i|) (0 where not nonzero)
  F pdf;              ///< the lobe's pdf of wi (visible normals, Walter eq. 14)
  MaskOf<F> nonzero;  ///< false: eval is 0
  // Written out rather than as member initializers: an implicit constructor would be compiled
  // outside the SIMD target's attributes (GCC), and could not inline the lane constructors.
  GgxTermsOf() : cosOM(0.0f), scale(0.0f), pdf(0.0f), nonzero(false) {}
};

/// f = F D G / (4 |cos_o cos_i|) with height-correlated G = 1 / ((1 + Lambda(wo)) +
/// Lambda(wi)), and pdf = D_wo(wm) / (4 |wo.wm|) with the visible normals' density D_wo =
/// G1(wo) D |wo.wm| / |cos_o|, G1(wo) = 1 / (1 + Lambda(wo)): the two share the half vector, D
/// and 1 + Lambda(wo). Zero where wo and wi are on opposite sides or opposite directions.
/// D and Lambda, isotropic (alphaY not read) or anisotropic, chosen at compile time.
template <bool kAniso, class V3, class F>
TRAY_LANE F ggxDOf(F alpha, F alphaY, const V3& wm) {
  if constexpr (kAniso)
    return ggxDAniso(alpha, alphaY, wm);
  else
    return ggxD(alpha, wm);
}
template <bool kAniso, class V3, class F>
TRAY_LANE F ggxLambdaOf(F alpha, F alphaY, const V3& w) {
  if constexpr (kAniso)
    return ggxLambdaAniso(alpha, alphaY, w);
  else
    return ggxLambda(alpha, w);
}
/// kAniso: the anisotropic D and Lambda with alphaX = alpha, alphaY (KHR_materials_anisotropy);
/// otherwise alphaY is not read. ggxTerms and ggxTermsAniso below name the two.
template <bool kAniso, class V3, class F>
TRAY_LANE GgxTermsOf<F> ggxTermsOf(F alpha, F alphaY, const V3& wo, const V3& wi) {
  GgxTermsOf<F> t;
  V3 wm = wi + wo;
  const auto valid = wo.z * wi.z > F(0.0f) && lengthSquared(wm) != F(0.0f);
  if (noneOf(valid)) return t;
  wm = normalize(wm);
  wm = select(wm.z < F(0.0f), -wm, wm);
  const F d = ggxDOf<kAniso>(alpha, alphaY, wm);
  const F onePlusLambdaO = F(1.0f) + ggxLambdaOf<kAniso>(alpha, alphaY, wo);
  const F cosOM = dot(wo, wm);
  const F pdf = ggxVisibleD(wo, wm, d, onePlusLambdaO) / (F(4.0f) * absOf(cosOM));
  const F cosO = absOf(wo.z), cosI = absOf(wi.z);
  const F scale = d * (F(1.0f) / (onePlusLambdaO + ggxLambdaOf<kAniso>(alpha, alphaY, wi))) /
                  (F(4.0f) * cosO * cosI);
  t.cosOM = select(valid, cosOM, F(0.0f));
  t.pdf = select(valid, pdf, F(0.0f));
  t.nonzero = valid && !(cosO == F(0.0f) || cosI == F(0.0f));
  t.scale = select(t.nonzero, scale, F(0.0f));
  return t;
}
template <class V3, class F>
TRAY_LANE GgxTermsOf<F> ggxTerms(F alpha, const V3& wo, const V3& wi) {
  return ggxTermsOf<false>(alpha, alpha, wo, wi);
}
template <class V3, class F>
TRAY_LANE GgxTermsOf<F> ggxTermsAniso(F alphaX, F alphaY, const V3& wo, const V3& wi) {
  return ggxTermsOf<true>(alphaX, alphaY, wo, wi);
}

/// The sampled direction of a non-delta lobe: visible normals on the upper side, wo mirrored
/// about one, the answer mirrored back for wo below. False (per lane) where wi falls below the
/// microsurface: no sample (pbrt-v4 does the same).
/// alphaY: KHR_materials_anisotropy's (equal to alpha: the isotropic lobe's floats).
template <class V3, class V2, class F>
TRAY_LANE MaskOf<F> ggxSampleDirection(F alpha, F alphaY, const V3& wo, const V2& u, V3& wi) {
  const auto below = wo.z < F(0.0f);
  const V3 woUp = select(below, -wo, wo);
  const V3 wm = ggxSampleVisibleNormalAniso(alpha, alphaY, woUp, u);
  wi = -woUp + F(2.0f) * dot(woUp, wm) * wm;
  const auto ok = !(wi.z <= F(0.0f));
  wi = select(below, -wi, wi);
  return ok;
}
template <class V3, class V2, class F>
TRAY_LANE MaskOf<F> ggxSampleDirection(F alpha, const V3& wo, const V2& u, V3& wi) {
  return ggxSampleDirection(alpha, alpha, wo, u, wi);
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

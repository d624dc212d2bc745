// glTF's metal and plastic mixture (Bsdf, materials/bsdf.h): the lobes' probabilities at wo,
// the mixture's value and pdf at (wo, wi), and its sample over the GGX and Lambert lobes,
// written once over the lane type (core/lane_ops.h, docs/lanes.md). Bsdf calls these for its
// mixtures (adding its glass lobe's terms, which stay scalar); the SIMD glossy stage includes
// this file again in each target's pass.
#ifdef TRAY_LANES_SIMD
#if defined(MATERIALS_GGX_MIXTURE_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef MATERIALS_GGX_MIXTURE_LANES_H_SIMD_
#undef MATERIALS_GGX_MIXTURE_LANES_H_SIMD_
#else
#define MATERIALS_GGX_MIXTURE_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(MATERIALS_GGX_MIXTURE_LANES_H_SCALAR_)
#define MATERIALS_GGX_MIXTURE_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "materials/fresnel_lanes.h"
#include "materials/ggx_reflection_lanes.h"
#include "materials/lambert_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// The mixture at one shading point, as Bsdf::initLobes weighs it: metallic x GGX metal
/// (Schlick Fresnel, F0 = albedo), (1 - metallic) transmission x glass, the rest plastic: coat
/// x a GGX dielectric coat over (1 - coat F(cos_o)) x Lambert(albedo). One alpha for both GGX
/// lobes. The On masks: the lobes eval adds (weight > 0, and the lobe kind asked for).
template <class V3>
struct GgxMixtureOf {
  using F = decltype(V3::x);
  F wMetal, wGlass, wPlastic, coat, alpha;
  V3 albedo;
  MaskOf<F> metalOn, glassOn, coatOn, diffuseOn;
  /// alpha below GgxDistribution::kSmoothAlpha: the GGX lobes are mirrors (delta lobes the
  /// caller samples), with no terms here.
  MaskOf<F> ggxDelta;
};

/// Bsdf::initLobes' weights from glTF's metallic, transmission and roughness (alpha =
/// ggxAlpha(roughness^2)): the coat strength fades from 1 to 0 as
/// roughness goes 0.9 -> 1, so roughness 1 with metallic 0 is exactly Lambert.
template <class V3, class F>
TRAY_LANE GgxMixtureOf<V3> ggxMixture(F metallic, F transmission, F roughness, const V3& albedo) {
  GgxMixtureOf<V3> x;
  x.wMetal = clampOf(metallic, F(0.0f), F(1.0f));
  x.wGlass = (F(1.0f) - x.wMetal) * clampOf(transmission, F(0.0f), F(1.0f));
  x.wPlastic = F(1.0f) - x.wMetal - x.wGlass;
  x.coat = clampOf((F(1.0f) - roughness) * F(10.0f), F(0.0f), F(1.0f));
  x.alpha = ggxAlpha(roughness * roughness);
  x.albedo = albedo;
  x.metalOn = x.wMetal > F(0.0f);
  x.glassOn = x.wGlass > F(0.0f);
  x.coatOn = x.wPlastic > F(0.0f) && x.coat > F(0.0f);
  x.diffuseOn = x.wPlastic > F(0.0f);
  x.ggxDelta = x.alpha < F(kGgxSmoothAlpha);
  return x;
}

/// Each lobe's probability of being sampled: roughly its share of the reflected energy (any
/// positive choice is unbiased), normalised; coatFresnel = coat F_coat(wo), which the Lambert
/// lobe's weight also reads.
template <class F>
struct MixtureProbabilitiesOf {
  F metal, glass, coat, diffuse, coatFresnel;
};
template <class V3, class F>
TRAY_LANE MixtureProbabilitiesOf<F> mixtureProbabilities(const GgxMixtureOf<V3>& x, F coatFresnel) {
  MixtureProbabilitiesOf<F> p;
  p.coatFresnel = coatFresnel;
  p.metal = x.wMetal;
  p.glass = x.wGlass;
  p.coat = x.wPlastic * coatFresnel;
  p.diffuse = x.wPlastic * (F(1.0f) - coatFresnel) * maxComponent(x.albedo);
  const F sum = p.metal + p.glass + p.coat + p.diffuse;
  const auto positive = sum > F(0.0f);
  const F inv = F(1.0f) / sum;
  p.metal = select(positive, p.metal * inv, p.metal);
  p.glass = select(positive, p.glass * inv, p.glass);
  p.coat = select(positive, p.coat * inv, p.coat);
  p.diffuse = select(positive, p.diffuse * inv, p.diffuse);
  return p;
}

/// The coat's weight seen from wo, coat F(|cos_o|), for an untinted coat of relative IOR eta.
template <class F>
TRAY_LANE F coatFresnelOf(F coat, F woZ, F eta) {
  return select(coat > F(0.0f), coat * fresnelDielectric(absOf(woZ), eta), F(0.0f));
}

/// The mixture's value and pdf at (wo, wi) in the local frame, given p = its probabilities at
/// wo; ggxPdf gets the GGX lobes' own pdf. The lobes that stay scalar come in as callables:
/// coatFresnel(cosOM) is the coat's Fresnel colour at the microfacet cosine (exact dielectric,
/// or KHR_materials_specular's tint); glass(wo, wi, glassPdf) the glass lobe's value where eval
/// includes it and its pdf where p.glass > 0 (0 where there is none: noGlass). Each sum in
/// Bsdf's order, a lobe left out adding 0 (to a sum that is never -0: the same bits as
/// skipping it).
/// The metal lobe's Fresnel: glTF's Schlick with F0 = albedo, unless the caller passes its
/// own metalFresnel(albedo, cosOM) (the scalar Bsdf's iridescent metal, which stays scalar).
struct SchlickMetal {
  template <class V3, class F>
  TRAY_LANE V3 operator()(const V3& albedo, F cosOM) const {
    return fresnelSchlick(albedo, cosOM);
  }
};
template <class V3, class F, class CoatFresnel, class Glass, class MetalFresnel = SchlickMetal>
TRAY_LANE V3 mixtureEvalPdf(const GgxMixtureOf<V3>& x, const MixtureProbabilitiesOf<F>& p,
                            const V3& wo, const V3& wi, CoatFresnel coatFresnel, Glass glass,
                            F& pdf, F& ggxPdf, MetalFresnel metalFresnel = {}) {
  const V3 zero{F(0.0f), F(0.0f), F(0.0f)};
  const auto ggxOn =
      (x.metalOn || x.coatOn || p.metal > F(0.0f) || p.coat > F(0.0f)) && !x.ggxDelta;
  GgxTermsOf<F> t;
  if (anyOf(ggxOn)) {
    t = ggxTerms(x.alpha, wo, wi);
    // Lanes whose GGX lobes are off (mirrors, or unused) add nothing, as for one float.
    t.nonzero = t.nonzero && ggxOn;
    t.pdf = select(ggxOn, t.pdf, F(0.0f));
  }
  ggxPdf = t.pdf;
  // Each term only where some lane has it: for one float, the scalar Bsdf's branches.
  V3 f = zero;
  if (anyOf(x.metalOn)) {
    const V3 metal = select(t.nonzero, metalFresnel(x.albedo, t.cosOM) * t.scale, zero);
    f = f + select(x.metalOn, x.wMetal * metal, zero);
  }
  F glassPdf(0.0f);
  if (anyOf(x.glassOn || p.glass > F(0.0f))) {
    const V3 glassF = glass(wo, wi, glassPdf);
    f = f + select(x.glassOn, x.wGlass * glassF, zero);
  }
  if (anyOf(x.coatOn)) {
    const V3 coat = select(t.nonzero, coatFresnel(t.cosOM) * t.scale, zero);
    f = f + select(x.coatOn, (x.wPlastic * x.coat) * coat, zero);
  }
  F lambertPdf(0.0f);
  const auto lambertOn = x.diffuseOn || p.diffuse > F(0.0f);
  if (anyOf(lambertOn)) {
    const V3 lambert = lambertEvalPdf(x.albedo, wo.z, wi.z, lambertPdf);
    f = f + select(x.diffuseOn, (x.wPlastic * (F(1.0f) - p.coatFresnel)) * lambert, zero);
  }
  pdf = F(0.0f);
  pdf = pdf + select(p.metal > F(0.0f), p.metal * t.pdf, F(0.0f));
  pdf = pdf + select(p.glass > F(0.0f), p.glass * glassPdf, F(0.0f));
  pdf = pdf + select(p.coat > F(0.0f), p.coat * t.pdf, F(0.0f));
  pdf = pdf + select(p.diffuse > F(0.0f), p.diffuse * lambertPdf, F(0.0f));
  return f;
}

/// The glass lobe of a mixture that has none.
struct NoGlass {
  template <class V3, class F>
  TRAY_LANE V3 operator()(const V3&, const V3&, F& glassPdf) const {
    glassPdf = F(0.0f);
    return V3{F(0.0f), F(0.0f), F(0.0f)};
  }
};

/// A sample of the mixture's metal, coat or Lambert lobe, chosen by uc against the
/// probabilities' cdf (metal, glass, coat, diffuse; a lane whose uc falls on glass is the
/// caller's), the direction from u (GGX visible normals or the cosine lobe), then the
/// mixture's value and pdf there. pdf 0 (no sample) where the lobe has no probability, its own
/// sample is invalid (no direction above the microsurface, or none its lobe gives density), or the
/// mixture's pdf is not positive and finite.
/// Below the smooth limit (x.ggxDelta) the metal and coat lobes are mirrors: their sample is
/// the mirrored direction with f = weight Fresnel(cos_o) / |cos_i| and the lobe's probability
/// as pdf (`delta`; none where wo lies in the surface), as Bsdf::sampleLocal weighs a delta
/// lobe's sample in a mixture.
template <class V3>
struct MixtureSampleOf {
  V3 wi, f;
  decltype(V3::x) pdf;
  MaskOf<decltype(V3::x)> delta;
};
template <class V3, class V2, class F, class CoatFresnel, class Glass,
          class MetalFresnel = SchlickMetal>
TRAY_LANE MixtureSampleOf<V3> mixtureSample(const GgxMixtureOf<V3>& x,
                                            const MixtureProbabilitiesOf<F>& p, const V3& wo, F uc,
                                            const V2& u, CoatFresnel coatFresnel, Glass glass,
                                            MetalFresnel metalFresnel = {}) {
  const V3 zero{F(0.0f), F(0.0f), F(0.0f)};
  const auto pastMetal = uc >= p.metal;
  const auto lambert = pastMetal && uc >= p.metal + p.glass + p.coat;
  const F prob = select(lambert, p.diffuse, select(pastMetal, p.coat, p.metal));
  MixtureSampleOf<V3> s;
  auto lobeValid = lambert;  // Lambert's pdf is positive (sampleCosineHemisphere's floor)
  s.wi = zero;
  if (anyOf(lambert)) s.wi = lambertSample(x.albedo, wo.z, u).wi;
  if (!allOf(lambert)) {
    V3 wiGgx;
    const auto ggxValid = ggxSampleDirection(x.alpha, wo, u, wiGgx) && wo.z != F(0.0f);
    s.wi = select(lambert, s.wi, wiGgx);
    lobeValid = lobeValid || (!lambert && ggxValid);
  }
  F pdf, ggxPdf;
  s.f = mixtureEvalPdf(x, p, wo, s.wi, coatFresnel, glass, pdf, ggxPdf, metalFresnel);
  // A GGX lobe's own sample the lobe gives no density: dropped.
  lobeValid = lobeValid && (lambert || ggxPdf > F(0.0f));
  const auto valid = prob > F(0.0f) && lobeValid && pdf > F(0.0f) && isFiniteOf(pdf);
  s.pdf = select(valid, pdf, F(0.0f));
  s.delta = x.ggxDelta && !lambert;
  if (anyOf(s.delta)) {  // mirrors: GgxReflectionLobe::sample's delta branch, then weighted
    const V3 mirror{-wo.x, -wo.y, wo.z};
    const V3 fresnel = select(pastMetal, coatFresnel(wo.z), metalFresnel(x.albedo, wo.z));
    const F weight = select(pastMetal, x.wPlastic * x.coat, x.wMetal);
    s.wi = select(s.delta, mirror, s.wi);
    s.f = select(s.delta, fresnel / absOf(mirror.z) * weight, s.f);
    s.pdf = select(s.delta, select(prob > F(0.0f) && wo.z != F(0.0f), prob, F(0.0f)), s.pdf);
  }
  return s;
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

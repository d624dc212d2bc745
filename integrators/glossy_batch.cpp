// Highway's dynamic dispatch, as integrators/matte_batch.cpp: compiled once per x86 target,
// with -ffp-contract=off (integrators/CMakeLists.txt). Every lane repeats PathEstimator::step's
// arithmetic for Bsdf's metal and plastic mixture, term by term in its order (initLobes'
// weights, computeProbabilities, mixtureEvalPdf with GgxReflectionLobe::terms, Schlick's and
// the exact dielectric Fresnel, sampleLocal's lobe choice, GgxDistribution::
// sampleVisibleNormal, LambertLobe::sample; EnvironmentLight::sample and AreaLight::
// sampleTriangle; powerHeuristic, setSpawnRay and setSpawnRayTo), so the bits are the same.
// Cosines and sines are core/sampling.h's polynomials, vectorised (SinCosQuarterPi).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/glossy_batch.cpp"
#include "integrators/glossy_batch.h"

#include <cmath>

#include "core/simd_lanes.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: Vec3 arithmetic over lanes, the stages' shared pieces.
#include "core/vec3_simd-inl.h"
#include "integrators/shading_simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// MatteBatch::useful() is false without a SIMD target: never called.
void GlossyVertices(const float*, const Color&, ShadingLanes&) {}
#else

/// fresnelDielectric(c, eta) for c = |cos| >= 0 (the flip for light from below never applies).
HWY_INLINE VF FresnelDielectric(VF c, VF eta) {
  const DF df;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  c = StdClamp(c, hn::Set(df, -1.0f), one);
  const VF sin2T = hn::Div(one - c * c, eta * eta);
  const VF cosT = hn::Sqrt(StdMax(zero, one - sin2T));
  const VF rParallel = hn::Div(eta * c - cosT, eta * c + cosT);
  const VF rPerpendicular = hn::Div(c - eta * cosT, c + eta * cosT);
  const VF r = hn::Div(rParallel * rParallel + rPerpendicular * rPerpendicular, hn::Set(df, 2.0f));
  return hn::IfThenElse(hn::Ge(sin2T, one), one, r);  // total internal reflection
}

/// Bsdf::initLobes for a metal and plastic mixture, and computeProbabilities at wo: what
/// mixtureEvalPdf reads at every (wo, wi) of the vertex, computed once.
struct Mixture {
  VF wMetal, wPlastic, coat, alpha, eta;
  V3 albedo;  ///< the metal's F0 and the Lambert lobe's albedo
  /// The lobes mixtureEvalPdf adds: metal (wMetal > 0), plastic (wPlastic > 0), its coat
  /// (and coat > 0); ggxOn: it computes the GGX terms at all.
  MF metalOn, plasticOn, coatOn, ggxOn;
  VF coatWeight, diffuseWeight;    ///< wPlastic coat and wPlastic (1 - coatFresnel(wo))
  VF fc, pMetal, pCoat, pDiffuse;  ///< coatFresnel(wo) and the lobes' probabilities
  MF pMetalOn, pCoatOn, pDiffuseOn;  ///< the probabilities that are > 0
  Mixture(const Fields& f, VF woz) : eta(f.load(f.m.eta)), albedo(f.load(f.m.albedo)) {
    const DF df;
    const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
    wMetal = StdClamp(f.load(f.m.metallic), zero, one);
    wPlastic = one - wMetal;  // - wGlass_, a zero: the same bits
    const VF roughness = f.load(f.m.roughness);
    coat = StdClamp((one - roughness) * hn::Set(df, 10.0f), zero, one);
    alpha = StdMax(roughness * roughness, hn::Set(df, 1e-4f));  // GgxDistribution's
    metalOn = hn::Gt(wMetal, zero);
    plasticOn = hn::Gt(wPlastic, zero);
    coatOn = hn::And(plasticOn, hn::Gt(coat, zero));
    fc = hn::IfThenElseZero(hn::Gt(coat, zero), coat * FresnelDielectric(hn::Abs(woz), eta));
    pMetal = wMetal;
    pCoat = wPlastic * fc;
    pDiffuse = (wPlastic * (one - fc)) * StdMax(albedo.x, StdMax(albedo.y, albedo.z));
    // ((metal + glass) + coat) + diffuse with glass a zero: the same bits up to the sign of
    // a zero sum, which only meets > 0.
    const VF sum = (pMetal + pCoat) + pDiffuse;
    const MF positive = hn::Gt(sum, zero);
    const VF inv = hn::Div(one, sum);
    pMetal = hn::IfThenElse(positive, pMetal * inv, pMetal);
    pCoat = hn::IfThenElse(positive, pCoat * inv, pCoat);
    pDiffuse = hn::IfThenElse(positive, pDiffuse * inv, pDiffuse);
    pMetalOn = hn::Gt(pMetal, zero), pCoatOn = hn::Gt(pCoat, zero);
    pDiffuseOn = hn::Gt(pDiffuse, zero);
    ggxOn = hn::Or(hn::Or(metalOn, coatOn), hn::Or(pMetalOn, pCoatOn));
    coatWeight = wPlastic * coat;
    diffuseWeight = wPlastic * (one - fc);
  }
};

/// GgxDistribution::lambda.
HWY_INLINE VF Lambda(VF alpha, VF z) {
  const DF df;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const VF cos2 = z * z;
  const VF tan2 = hn::Div(StdMax(zero, one - cos2), cos2);
  const VF l = hn::Div(hn::Sqrt(one + (alpha * alpha) * tan2) - one, hn::Set(df, 2.0f));
  return hn::IfThenElse(hn::Le(cos2, zero), hn::Inf(df), l);
}

/// GgxReflectionLobe::terms.
struct Terms {
  VF cosOM, scale, pdf;
  MF nonzero;
};
HWY_INLINE Terms GgxTerms(VF alpha, const V3& wo, const V3& wi) {
  const DF df;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f), four = hn::Set(df, 4.0f);
  const MF same = hn::Gt(wo.z * wi.z, zero);
  V3 wm = {wi.x + wo.x, wi.y + wo.y, wi.z + wo.z};
  const MF some = hn::Ne(Dot(wm, wm), zero);
  wm = Normalize(wm);
  wm = NegateUnless(hn::Not(hn::Lt(wm.z, zero)), wm);
  // GgxDistribution::D.
  const VF cos2 = wm.z * wm.z, sin2 = StdMax(zero, one - cos2), a2 = alpha * alpha;
  const VF e = cos2 + hn::Div(sin2, a2);
  const VF d =
      hn::IfThenElseZero(hn::Gt(wm.z, zero), hn::Div(one, ((hn::Set(df, kPi) * a2) * e) * e));
  const VF onePlusLambdaO = one + Lambda(alpha, wo.z);
  const VF cosOM = Dot(wo, wm);
  // GgxDistribution::visibleD.
  const VF c = hn::Abs(wo.z);
  const VF visible = hn::IfThenZeroElse(
      hn::Eq(c, zero), ((hn::Div(hn::Div(one, onePlusLambdaO), c)) * d) * hn::Abs(Dot(wo, wm)));
  const VF pdf = hn::Div(visible, four * hn::Abs(cosOM));
  const VF cosI = hn::Abs(wi.z);
  const VF scale =
      hn::Div(d * hn::Div(one, onePlusLambdaO + Lambda(alpha, wi.z)), (four * c) * cosI);
  Terms t;
  const MF valid = hn::And(same, some);
  t.cosOM = hn::IfThenElseZero(valid, cosOM);
  t.pdf = hn::IfThenElseZero(valid, pdf);
  t.nonzero = hn::AndNot(hn::Or(hn::Eq(c, zero), hn::Eq(cosI, zero)), valid);
  t.scale = hn::IfThenElseZero(t.nonzero, scale);
  return t;
}

/// Bsdf::mixtureEvalPdf: the mixture's value and pdf at (wo, wi) in the local frame, and the
/// GGX lobes' own pdf.
struct Evaluated {
  V3 f;
  VF pdf, ggxPdf;
};
HWY_INLINE Evaluated MixtureEvalPdf(const Mixture& x, const V3& wo, const V3& wi) {
  const DF df;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const Terms t = GgxTerms(x.alpha, wo, wi);
  Evaluated r;
  r.ggxPdf = hn::IfThenElseZero(x.ggxOn, t.pdf);
  // Schlick's metal Fresnel with F0 = albedo, and the coat's exact one, at wo . wm.
  const VF m = StdClamp(one - hn::Abs(t.cosOM), zero, one);
  const VF m5 = ((m * m) * (m * m)) * m;
  const V3& f0 = x.albedo;
  const V3 metal = {hn::IfThenElseZero(t.nonzero, (f0.x + (one - f0.x) * m5) * t.scale),
                    hn::IfThenElseZero(t.nonzero, (f0.y + (one - f0.y) * m5) * t.scale),
                    hn::IfThenElseZero(t.nonzero, (f0.z + (one - f0.z) * m5) * t.scale)};
  const VF coat =
      hn::IfThenElseZero(t.nonzero, FresnelDielectric(hn::Abs(t.cosOM), x.eta) * t.scale);
  const MF same = hn::Gt(wo.z * wi.z, zero);  // LambertLobe's
  const VF invPi = hn::Set(df, 1.0f / kPi);
  // ((0 + metal) + coat) + diffuse, a term left out where the scalar code skips it (+0 added
  // to a sum that is never -0: the same bits).
  const auto sum = [&](VF metalC, VF albedoC) {
    const VF diffuse = hn::IfThenElseZero(same, albedoC * invPi);
    return ((zero + hn::IfThenElseZero(x.metalOn, x.wMetal * metalC)) +
            hn::IfThenElseZero(x.coatOn, x.coatWeight * coat)) +
           hn::IfThenElseZero(x.plasticOn, x.diffuseWeight * diffuse);
  };
  r.f = {sum(metal.x, x.albedo.x), sum(metal.y, x.albedo.y), sum(metal.z, x.albedo.z)};
  const VF lambertPdf =
      hn::IfThenElseZero(same, hn::Div(StdMax(zero, hn::Abs(wi.z)), hn::Set(df, kPi)));
  r.pdf = ((zero + hn::IfThenElseZero(x.pMetalOn, x.pMetal * t.pdf)) +
           hn::IfThenElseZero(x.pCoatOn, x.pCoat * t.pdf)) +
          hn::IfThenElseZero(x.pDiffuseOn, x.pDiffuse * lambertPdf);
  return r;
}

/// Next-event estimation of one vector of vertices: the chosen triangle's or the constant
/// environment's sample, the mixture toward it, powerHeuristic and the shadow ray. Out of
/// line, as ScatterSample: inlined into GlossyVertices, clang's sanitizer build of this file
/// (tools/fuzz.sh) took 6.5 minutes and 4.6 GB; so 77 s and 0.9 GB, for 0.2% more
/// instructions (callgrind, heavy spheres).
template <bool kEnvironment>
HWY_NOINLINE void LightSample(const Fields& f, const float* table, const Color& environmentLe,
                              const Basis& frame, const Mixture& x, const V3& wo) {
  const DF df;
  const DI di;
  const V3 p = f.load(f.m.p), ng = f.load(f.m.ng);
  const ChosenLightSample ls = SampleChosenLight<kEnvironment>(f, table, environmentLe, p, frame.n);
  // Bsdf::eval(wo, wi, pdf) times |cos| at the receiver.
  const Evaluated e = MixtureEvalPdf(x, wo, frame.toLocal(ls.wi));
  const VF absCos = hn::Abs(Dot(ls.wi, frame.n));
  const V3 fr = {e.f.x * absCos, e.f.y * absCos, e.f.z * absCos};
  const MF ok = hn::AndNot(Black(fr), ls.ok);
  const VF scale = hn::Div(PowerHeuristic(ls.pdf, e.pdf), ls.pdf);
  const V3 beta = f.load(f.m.beta);
  const V3& Le = ls.Le;
  f.store(f.m.contribution, {((beta.x * fr.x) * Le.x) * scale, ((beta.y * fr.y) * Le.y) * scale,
                             ((beta.z * fr.z) * Le.z) * scale});
  StoreShadowRay<kEnvironment>(f, ls, p, ng);
  f.store(f.m.lit, hn::VecFromMask(di, hn::RebindMask(di, ok)));
}

/// GgxReflectionLobe::sampleDirection from the polar disk point (px, py): the visible normal
/// (GgxDistribution::sampleVisibleNormal, Heitz 2018) and wo mirrored about it; `ok` where wi
/// is above the microsurface.
HWY_INLINE V3 GgxDirection(VF alpha, const V3& wo, VF px, VF py, MF& ok) {
  const DF df;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const MF below = hn::Lt(wo.z, zero);
  const V3 woUp = NegateUnless(hn::Not(below), wo);
  V3 wh = Normalize({alpha * woUp.x, alpha * woUp.y, woUp.z});
  wh = NegateUnless(hn::Not(hn::Lt(wh.z, zero)), wh);
  // cross((0, 0, 1), wh), written out as the scalar cross product computes it.
  const V3 up = {zero * wh.z - one * wh.y, one * wh.x - zero * wh.z, zero * wh.y - zero * wh.x};
  const V3 t1 = Select(hn::Lt(wh.z, hn::Set(df, 0.99999f)), Normalize(up), {one, zero, zero});
  const V3 t2 = {wh.y * t1.z - wh.z * t1.y, wh.z * t1.x - wh.x * t1.z, wh.x * t1.y - wh.y * t1.x};
  const VF h = hn::Sqrt(StdMax(zero, one - px * px));
  const VF s = hn::Div(one + wh.z, hn::Set(df, 2.0f));
  py = (one - s) * h + s * py;
  const VF pz = hn::Sqrt(StdMax(zero, (one - px * px) - py * py));
  const V3 nh = {(px * t1.x + py * t2.x) + pz * wh.x, (px * t1.y + py * t2.y) + pz * wh.y,
                 (px * t1.z + py * t2.z) + pz * wh.z};
  const V3 wm = Normalize({alpha * nh.x, alpha * nh.y, StdMax(hn::Set(df, 1e-6f), nh.z)});
  const VF d = hn::Set(df, 2.0f) * Dot(woUp, wm);
  const V3 wi = {hn::Neg(woUp.x) + wm.x * d, hn::Neg(woUp.y) + wm.y * d,
                 hn::Neg(woUp.z) + wm.z * d};
  ok = hn::Not(hn::Le(wi.z, zero));
  return NegateUnless(hn::Not(below), wi);
}

/// BSDF sampling of one vector of vertices: Bsdf::sampleLocal's lobe choice, the GGX lobes'
/// visible normals or Lambert's cosine lobe, the mixture's value and pdf there (their checks
/// as mixtureGgxSample and sampleLocal make them), the throughput update and setSpawnRay.
HWY_NOINLINE void ScatterSample(const Fields& f, const Basis& frame, const Mixture& x,
                                const V3& wo) {
  const DF df;
  const VF zero = hn::Zero(df);
  // The lobe: metal below the first cdf step, the coat below the third, else Lambert (the
  // second step, glass, has probability 0: no draw lands on it).
  const VF uc = f.load(f.m.lobeDraw);
  const MF pastMetal = hn::Ge(uc, x.pMetal);
  const MF lambert = hn::And(pastMetal, hn::Ge(uc, x.pMetal + x.pCoat));
  const VF prob = hn::IfThenElse(lambert, x.pDiffuse, hn::IfThenElse(pastMetal, x.pCoat, x.pMetal));
  // Both disk points: Lambert's lanes take the concentric one, the GGX lobes' the polar one.
  VF v1, v2, dx, dy, px, py;
  f.load(f.m.bsdfDraw, v1, v2);
  ConcentricDisk(v1, v2, dx, dy);
  PolarDisk(v1, v2, px, py);
  // LambertLobe::sample on wo's side.
  const VF z = CosineZ(dx, dy);
  const V3 wiLambert = {dx, dy, hn::IfThenElse(hn::Lt(wo.z, zero), hn::Neg(z), z)};
  const MF lambertValid =
      hn::Gt(hn::Div(StdMax(zero, hn::Abs(wiLambert.z)), hn::Set(df, kPi)), zero);
  MF ggxValid;
  const V3 wiGgx = GgxDirection(x.alpha, wo, px, py, ggxValid);
  ggxValid = hn::And(ggxValid, hn::Ne(wo.z, zero));
  const V3 wiLocal = Select(lambert, wiLambert, wiGgx);
  const Evaluated e = MixtureEvalPdf(x, wo, wiLocal);
  // mixtureGgxSample drops a sample its own lobe gives no density; both drop a pdf that is not
  // positive and finite.
  const MF lobeValid = hn::Or(hn::And(lambert, lambertValid),
                              hn::AndNot(lambert, hn::And(ggxValid, hn::Gt(e.ggxPdf, zero))));
  const MF valid = hn::And(hn::And(hn::Gt(prob, zero), lobeValid),
                           hn::And(hn::Gt(e.pdf, zero), hn::IsFinite(e.pdf)));
  const VF pdf = hn::IfThenElseZero(valid, e.pdf);
  const V3 wi = frame.toWorld(wiLocal);
  // beta *= f (|cos| / pdf).
  const VF s = hn::Div(hn::Abs(Dot(wi, frame.n)), pdf);
  const V3 beta = f.load(f.m.beta);
  f.store(f.m.nextBeta, {beta.x * (e.f.x * s), beta.y * (e.f.y * s), beta.z * (e.f.z * s)});
  StoreNextRay(f, wi, pdf);
}

void GlossyVertices(const float* table, const Color& envLe, ShadingLanes& lanes) {
  const size_t n = hn::Lanes(DF());
  // Whole vectors: the inputs are padded (ShadingLanes::padInputs), and the outputs have room.
  for (size_t q = 0; q < lanes.count; q += n) {
    const Fields f{lanes, q};
    const Basis frame(f.load(f.m.n));
    const V3 wo = frame.toLocal(f.load(f.m.wo));
    const Mixture x(f, wo.z);
    if (hn::AllFalse(DF(), EnvironmentLanes(f)))
      LightSample<false>(f, table, envLe, frame, x, wo);
    else
      LightSample<true>(f, table, envLe, frame, x, wo);
    ScatterSample(f, frame, x, wo);
  }
}

#endif  // HWY_TARGET != HWY_SCALAR
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(GlossyVertices);

GlossyBatch::GlossyBatch(const MatteBatch& lights) : lights_(lights) {}

void GlossyBatch::compute(ShadingLanes& lanes) const {
  if (lanes.count == 0) return;
  lanes.padInputs();
  HWY_DYNAMIC_DISPATCH(GlossyVertices)(lights_.table(), lights_.environmentLe(), lanes);
}

}  // namespace tray
#endif  // HWY_ONCE

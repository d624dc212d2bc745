// KHR_materials_clearcoat: a smooth or GGX-rough dielectric coat over the whole material, as the
// extension's README ("Implementation") layers it:
//   f = c fc(wo, wi) + (1 - c Fc(cos_o)) f_base(wo, wi)
// with fc the coat's microfacet BRDF (exact dielectric Fresnel, IOR 1.5, i.e. F0 = 0.04), Fc
// its Fresnel seen from wo, and c = clearcoat. Light the coat reflects is taken from the base
// (the weight 1 - c Fc); the coat itself absorbs nothing. The coat has its own normal: the
// interpolated one, or clearcoatNormalTexture's.
#include "materials/bsdf.h"

#include "materials/fresnel.h"

namespace tray {

namespace {
/// The extension's coat: IOR 1.5 against air.
constexpr float kClearcoatIor = 1.5f;
/// The base's share of sampling is at least this estimate of its albedo: a black base still
/// gets samples (its lobes may be bright at other angles).
constexpr float kMinBaseEstimate = 0.05f;
}  // namespace

void Bsdf::initClearcoat(const ShadingMaterial& m) {
  clearcoat_ = std::clamp(m.clearcoat, 0.0f, 1.0f);
  const float r = std::clamp(m.clearcoatRoughness, 0.0f, 1.0f);
  ccLobe_.value = GgxReflectionLobe::dielectric(r * r, kClearcoatIor);
  // The coat's normal on the side of the base's frame (the side wo arrives from).
  Vec3 n = m.clearcoatN;
  const float len = length(n);
  if (!(len > 0) || !std::isfinite(len)) n = frame_.n;
  if (dot(n, frame_.n) < 0) n = -n;
  ccOwnFrame_ = !(n == frame_.n) && !(-n == frame_.n);
  ccFrame_.value = ccOwnFrame_ ? Frame::fromNormal(normalize(n)) : frame_;
  // How much the base reflects, roughly: its colour (metals, diffuse and glass all scale with
  // it). Only the sampling choice depends on it.
  baseEstimate_ = std::clamp(maxComponent(m.baseColor), kMinBaseEstimate, 1.0f);
}

float Bsdf::clearcoatFresnel(const Vec3& wo) const {
  return clearcoat_ * fresnelDielectric(std::fabs(dot(wo, ccFrame_->n)), kClearcoatIor);
}

float Bsdf::clearcoatProbability(float cFc) const {
  // The coat's share of the reflected energy against the base's (any choice in (0, 1) is
  // unbiased): c Fc against (1 - c Fc) x the base's albedo estimate.
  const float base = (1.0f - cFc) * baseEstimate_;
  return cFc > 0 ? cFc / (cFc + base) : 0.0f;
}

Color Bsdf::layeredEval(const Vec3& wo, const Vec3& wi, float& pdf) const {
  const float cFc = clearcoatFresnel(wo), pc = clearcoatProbability(cFc);
  const Vec3 woC = ccFrame_->toLocal(wo), wiC = ccFrame_->toLocal(wi);
  const GgxReflectionLobe::Terms coatTerms = ccLobe_->terms(woC, wiC);  // its eval and pdf
  Color coat = includes(kSpecularLobes) ? ccLobe_->eval(coatTerms) * clearcoat_ : Color(0.0f);
  // The integrator multiplies by the base normal's cosine; the coat's BRDF goes with its own.
  if (ccOwnFrame_ && !isBlack(coat)) {
    const float cosBase = std::fabs(dot(wi, frame_.n));
    coat *= cosBase > 0 ? absCosTheta(wiC) / cosBase : 0.0f;
  }
  float basePdf;
  const Color base = innerEval(wo, wi, basePdf);
  pdf = pc * coatTerms.pdf + (1.0f - pc) * basePdf;
  return coat + (1.0f - cFc) * base;
}

BsdfSample Bsdf::layeredSample(const Vec3& wo, float uc, Vec2 u) const {
  const float cFc = clearcoatFresnel(wo), pc = clearcoatProbability(cFc);
  BsdfSample s;
  if (uc < pc) {
    s = ccLobe_->sample(ccFrame_->toLocal(wo), u);
    if (!s.valid()) return s;
    s.wi = ccFrame_->toWorld(s.wi);
    if (s.delta) {
      // The mirror's coefficient F / |cos_coat| becomes c F / |cos_base| (the integrator
      // multiplies by the base normal's cosine), chosen with probability pc.
      const float cosBase = std::fabs(dot(s.wi, frame_.n));
      if (!(cosBase > 0)) return BsdfSample{};
      s.f *= clearcoat_ * (absCosTheta(ccFrame_->toLocal(s.wi)) / cosBase);
      s.pdf *= pc;
      return s;
    }
  } else {
    const float ucBase = std::min((uc - pc) / (1.0f - pc), 0.99999994f);
    s = innerSample(wo, ucBase, u);
    if (!s.valid()) return s;
    if (s.delta) {
      s.f *= 1.0f - cFc;
      s.pdf *= 1.0f - pc;
      return s;
    }
  }
  // A continuous direction: the mixture's value and density (both lobes could give it).
  s.f = layeredEval(wo, s.wi, s.pdf);
  if (!(s.pdf > 0) || !std::isfinite(s.pdf)) s.pdf = 0;
  return s;
}

}  // namespace tray

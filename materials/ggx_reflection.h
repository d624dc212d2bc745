#pragma once
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/iridescence.h"
#include "materials/microfacet.h"
// terms and the sampled direction, written once for scalar code and the SIMD stages.
#include "materials/ggx_reflection_lanes.h"

namespace tray {

/// Microfacet reflection (Walter et al. 2007, eq. 20): f = D G F / (4 |cos_o cos_i|), sampled
/// through visible normals. Fresnel is glTF's colored Schlick for metals, or the exact
/// dielectric Fresnel for the specular coat of plastics. Smooth limits become a mirror delta.
class GgxReflectionLobe {
 public:
  /// A metal: Schlick Fresnel with F0 = baseColor.
  static GgxReflectionLobe metal(float alpha, const Color& f0) { return {alpha, f0, 0.0f}; }
  /// An anisotropic metal or dielectric reflection (KHR_materials_anisotropy): alphaX along the
  /// local x axis. Returns `l` with its distribution stretched; alphaX = alphaY changes nothing.
  static GgxReflectionLobe anisotropic(GgxReflectionLobe l, float alphaX, float alphaY) {
    l.dist_ = GgxDistribution(alphaX, alphaY);
    return l;
  }
  /// A dielectric's reflection: exact Fresnel with eta = n_t / n_i.
  static GgxReflectionLobe dielectric(float alpha, float eta) { return {alpha, Color(0.0f), eta}; }
  /// The same with KHR_materials_specular's weight and F0 colour: the exact Fresnel curve
  /// remapped from [F0, 1] to [F0', 1] with F0' = min(F0 x colour, 1), then scaled by weight.
  /// This keeps the extension's F0 and F90 (README, "Implementation": Schlick's
  /// f0 + (1 - f0)(1 - cos)^5 with f0 = min(F0 x specularColor, 1), times specular) while the
  /// shape between them stays the exact dielectric one; colour 1 and weight 1 give the plain
  /// dielectric(). Per channel F <= weight <= 1: energy is never created.
  static GgxReflectionLobe dielectric(float alpha, float eta, float weight, const Color& colour) {
    GgxReflectionLobe l{alpha, Color(0.0f), eta};
    const float r = (eta - 1.0f) / (eta + 1.0f);
    l.f0Exact_ = std::min(r * r, 0.999f);
    l.f0_ = min(Color(l.f0Exact_) * colour, Color(1.0f));
    l.weight_ = weight;
    l.tinted_ = true;
    return l;
  }
  /// KHR_materials_iridescence: a thin film (IOR filmIor, thicknessNm nanometres) whose
  /// Fresnel (materials/iridescence.h) is mixed with the plain one by `factor`. The film's base
  /// is this lobe's F0: the metal's colour, or the dielectric's (tinted) F0. No change unless
  /// iridescenceApplies(factor, thicknessNm).
  void setIridescence(float factor, float filmIor, float thicknessNm) {
    if (!iridescenceApplies(factor, thicknessNm)) return;
    irid_ = factor, filmIor_ = filmIor, filmNm_ = thicknessNm;
    if (eta_ > 0) {
      const float r = (eta_ - 1.0f) / (eta_ + 1.0f);
      filmBase_ = tinted_ ? f0_ : Color(std::min(r * r, 0.999f));
    } else {
      filmBase_ = f0_;
    }
  }
  bool iridescent() const { return irid_ > 0; }
  bool isDelta() const { return dist_.effectivelySmooth(); }
  float alpha() const { return dist_.alpha(); }
  float alphaY() const { return dist_.alphaY(); }
  Color fresnel(float cosI) const {
    if (irid_ > 0) return iridescentMix(cosI);
    return plainFresnel(cosI);
  }
  Color eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, Vec2 u) const;

  /// What eval and pdf share at one (wo, wi), computed once: the half vector, D and Lambda(wo)
  /// (with the same operations as eval and pdf, so the same floats). They depend on alpha
  /// alone, so two lobes of one roughness (the mixture's metal and coat) share them and differ
  /// only in eval(Terms)'s Fresnel factor.
  using Terms = GgxTermsOf<float>;
  Terms terms(const Vec3& wo, const Vec3& wi) const;
  /// eval(wo, wi) from terms(wo, wi).
  Color eval(const Terms& t) const { return t.nonzero ? fresnel(t.cosOM) * t.scale : Color(0.0f); }
  /// sample's direction alone (for a non-delta lobe and wo.z != 0); false: no sample.
  bool sampleDirection(const Vec3& wo, Vec2 u, Vec3& wi) const;

 private:
  GgxReflectionLobe(float alpha, const Color& f0, float eta) : dist_(alpha), f0_(f0), eta_(eta) {}
  float fresnelDielectricAbs(float cosI) const;
  Color plainFresnel(float cosI) const {
    if (eta_ > 0 && tinted_) return tintedFresnel(fresnelDielectricAbs(cosI));
    return eta_ > 0 ? Color(fresnelDielectricAbs(cosI)) : fresnelSchlick(f0_, cosI);
  }
  /// (1 - factor) plain + factor film; the tinted dielectric's film also takes its weight.
  Color iridescentMix(float cosI) const;
  Color tintedFresnel(float F) const {
    const float t = std::max(0.0f, (F - f0Exact_) / (1.0f - f0Exact_));
    return weight_ * (f0_ + (Color(1.0f) - f0_) * t);
  }
  GgxDistribution dist_;
  Color f0_;
  float eta_;  ///< > 0: dielectric Fresnel with this eta; 0: Schlick with f0_
  bool tinted_ = false;  ///< dielectric with KHR_materials_specular: f0_ is F0', weight_ applies
  float f0Exact_ = 0, weight_ = 1;
  float irid_ = 0, filmIor_ = 1.3f, filmNm_ = 0;  ///< KHR_materials_iridescence (0: off)
  Color filmBase_{0.0f};
};

}  // namespace tray

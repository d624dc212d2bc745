#pragma once
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"

namespace tray {

/// Microfacet reflection (Walter et al. 2007, eq. 20): f = D G F / (4 |cos_o cos_i|), sampled
/// through visible normals. Fresnel is glTF's colored Schlick for metals, or the exact
/// dielectric Fresnel for the specular coat of plastics. Smooth limits become a mirror delta.
class GgxReflectionLobe {
 public:
  /// A metal: Schlick Fresnel with F0 = baseColor.
  static GgxReflectionLobe metal(float alpha, const Color& f0) { return {alpha, f0, 0.0f}; }
  /// A dielectric's reflection: exact Fresnel with eta = n_t / n_i.
  static GgxReflectionLobe dielectric(float alpha, float eta) { return {alpha, Color(0.0f), eta}; }
  bool isDelta() const { return dist_.effectivelySmooth(); }
  Color fresnel(float cosI) const {
    return eta_ > 0 ? Color(fresnelDielectricAbs(cosI)) : fresnelSchlick(f0_, cosI);
  }
  Color eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, Vec2 u) const;

 private:
  GgxReflectionLobe(float alpha, const Color& f0, float eta) : dist_(alpha), f0_(f0), eta_(eta) {}
  float fresnelDielectricAbs(float cosI) const;
  GgxDistribution dist_;
  Color f0_;
  float eta_;  ///< > 0: dielectric Fresnel with this eta; 0: Schlick with f0_
};

}  // namespace tray

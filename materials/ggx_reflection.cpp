#include "materials/ggx_reflection.h"

#include "materials/fresnel.h"

namespace tray {

float GgxReflectionLobe::fresnelDielectricAbs(float cosI) const {
  // Reflection stays on the side it arrived from: the outside (the coat faces outwards).
  return fresnelDielectric(std::fabs(cosI), eta_);
}

Color GgxReflectionLobe::iridescentMix(float cosI) const {
  // The film sits on the outside (air): the reference's outsideIOR 1 (iridescence.glsl).
  Color film = iridescentFresnel(1.0f, filmIor_, std::fabs(cosI), filmNm_, filmBase_);
  if (eta_ > 0 && tinted_) film *= weight_;
  return (1.0f - irid_) * plainFresnel(cosI) + irid_ * film;
}

Color GgxReflectionLobe::eval(const Vec3& wo, const Vec3& wi) const {
  return eval(terms(wo, wi));
}

float GgxReflectionLobe::pdf(const Vec3& wo, const Vec3& wi) const {
  return terms(wo, wi).pdf;
}

GgxReflectionLobe::Terms GgxReflectionLobe::terms(const Vec3& wo, const Vec3& wi) const {
  if (isDelta()) return {};
  if (dist_.anisotropic()) return ggxTermsAniso(dist_.alpha(), dist_.alphaY(), wo, wi);
  return ggxTerms(dist_.alpha(), wo, wi);
}

bool GgxReflectionLobe::sampleDirection(const Vec3& wo, Vec2 u, Vec3& wi) const {
  return ggxSampleDirection(dist_.alpha(), dist_.alphaY(), wo, u, wi);
}

BsdfSample GgxReflectionLobe::sample(const Vec3& wo, Vec2 u) const {
  BsdfSample s;
  if (wo.z == 0) return s;
  if (isDelta()) {
    s.wi = {-wo.x, -wo.y, wo.z};
    s.f = fresnel(wo.z) / absCosTheta(s.wi);
    s.pdf = 1.0f;
    s.delta = true;
    return s;
  }
  Vec3 wi;
  if (!sampleDirection(wo, u, wi)) return s;
  s.wi = wi;
  const Terms t = terms(wo, wi);  // eval and pdf in one pass
  s.pdf = t.pdf;
  s.f = eval(t);
  if (!(s.pdf > 0)) s.pdf = 0;
  return s;
}

}  // namespace tray

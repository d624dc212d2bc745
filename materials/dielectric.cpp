#include "materials/dielectric.h"

#include "materials/fresnel.h"

namespace tray {

bool DielectricLobe::halfVector(const Vec3& wo, const Vec3& wi, Vec3& wm, float& etap) const {
  float cosO = cosTheta(wo), cosI = cosTheta(wi);
  if (cosO == 0 || cosI == 0) return false;
  bool reflect = cosO * cosI > 0;
  etap = reflect ? 1.0f : (cosO > 0 ? eta_ : 1.0f / eta_);
  wm = wi * etap + wo;
  if (lengthSquared(wm) == 0) return false;
  wm = normalize(wm);
  if (wm.z < 0) wm = -wm;
  return dot(wm, wi) * cosI >= 0 && dot(wm, wo) * cosO >= 0;
}

Color DielectricLobe::filmFresnel(float cosI, float plain) const {
  if (plain >= 1.0f) return Color(1.0f);  // total internal reflection: no film changes it
  // The film sits on the outside (+z). Seen from inside, a lossless film reflects what it
  // reflects from outside at the refracted angle (its transmittance is the same both ways,
  // Stokes' relations), so it is evaluated at the outside cosine, from Snell's law.
  const float cosOut =
      cosI >= 0 ? cosI : std::sqrt(std::max(0.0f, 1.0f - eta_ * eta_ * (1.0f - cosI * cosI)));
  const float f0 = (eta_ - 1.0f) / (eta_ + 1.0f);
  // The reference's outsideIOR 1 (iridescence.glsl), as for the metal and the coat.
  const Color film =
      iridescentFresnel(1.0f, filmIor_, cosOut, filmNm_, Color(std::min(f0 * f0, 0.999f)));
  const Color mixed = (1.0f - irid_) * Color(plain) + irid_ * film;
  return {std::min(mixed.x, 1.0f), std::min(mixed.y, 1.0f), std::min(mixed.z, 1.0f)};
}

float DielectricLobe::reflectChoice(float cosI) const {
  const float plain = fresnelDielectric(cosI, eta_);
  if (irid_ == 0) return plain;
  const Color F = filmFresnel(cosI, plain);
  return (F.x + F.y + F.z) / 3.0f;
}

template <class R>
Color DielectricLobe::evalWith(const Vec3& wo, const Vec3& wi, const Vec3& wm, float etap,
                               const R& F) const {
  float cosO = cosTheta(wo), cosI = cosTheta(wi);
  if (cosO * cosI > 0)
    return Color(dist_.D(wm) * dist_.G(wo, wi) * F / std::fabs(4.0f * cosI * cosO));
  float denom = dot(wi, wm) + dot(wo, wm) / etap;
  denom = denom * denom * cosI * cosO;
  const R oneMinusF = reflectanceColour<R>(1.0f) - F;
  const R ft =
      dist_.D(wm) * oneMinusF * dist_.G(wo, wi) * std::fabs(dot(wi, wm) * dot(wo, wm) / denom);
  return tint_ * (ft / (etap * etap));
}

Color DielectricLobe::eval(const Vec3& wo, const Vec3& wi) const {
  if (isDelta()) return Color(0.0f);
  Vec3 wm;
  float etap;
  if (!halfVector(wo, wi, wm, etap)) return Color(0.0f);
  const float cosM = dot(wo, wm);
  const float F = fresnelDielectric(cosM, eta_);
  if (irid_ > 0) return evalWith(wo, wi, wm, etap, filmFresnel(cosM, F));
  return evalWith(wo, wi, wm, etap, F);
}

float DielectricLobe::pdf(const Vec3& wo, const Vec3& wi) const {
  if (isDelta()) return 0.0f;
  Vec3 wm;
  float etap;
  if (!halfVector(wo, wi, wm, etap)) return 0.0f;
  float R = reflectChoice(dot(wo, wm)), T = 1.0f - R;
  if (cosTheta(wo) * cosTheta(wi) > 0)
    return dist_.visibleD(wo, wm) / (4.0f * std::fabs(dot(wo, wm))) * R;
  // Refraction's Jacobian dwm/dwi (Walter et al. eq. 17).
  float denom = dot(wi, wm) + dot(wo, wm) / etap;
  float dwmDwi = std::fabs(dot(wi, wm)) / (denom * denom);
  return dist_.visibleD(wo, wm) * dwmDwi * T;
}

BsdfSample DielectricLobe::sampleSmooth(const Vec3& wo, float uc) const {
  DeltaSampleOf<Vec3> d;
  if (irid_ > 0) {
    const Color F = filmFresnel(wo.z, fresnelDielectric(wo.z, eta_));
    d = sampleSmoothDielectricWith(wo, eta_, tint_, uc, F, (F.x + F.y + F.z) / 3.0f);
  } else {
    d = sampleSmoothDielectric(wo, eta_, tint_, uc);
  }
  BsdfSample s;
  s.wi = d.wi, s.f = d.f, s.pdf = d.pdf;
  s.etaScale = d.etaScale;
  s.delta = true;
  s.transmission = d.transmission;
  return s;
}

BsdfSample DielectricLobe::sample(const Vec3& wo, float uc, Vec2 u) const {
  if (isDelta()) return sampleSmooth(wo, uc);
  BsdfSample s;
  if (wo.z == 0) return s;
  // Visible normals of the side wo is on.
  Vec3 woUp = wo.z < 0 ? -wo : wo;
  Vec3 wm = dist_.sampleVisibleNormal(woUp, u);  // on +z; Fresnel inverts eta for wo below
  float R = reflectChoice(dot(wo, wm));
  if (uc < R) {
    Vec3 wi = -wo + 2.0f * dot(wo, wm) * wm;
    if (!sameHemisphere(wo, wi)) return s;
    s.wi = wi;
  } else {
    float etap;
    Vec3 wi;
    if (!refractDirection(wo, wm, eta_, etap, wi)) return s;
    if (sameHemisphere(wo, wi) || wi.z == 0) return s;
    s.wi = wi;
    s.transmission = true;
    s.etaScale = 1.0f / (etap * etap);
  }
  s.pdf = pdf(wo, s.wi);
  s.f = eval(wo, s.wi);
  if (!(s.pdf > 0)) s.pdf = 0;
  return s;
}

}  // namespace tray

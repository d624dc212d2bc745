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

Color DielectricLobe::eval(const Vec3& wo, const Vec3& wi) const {
  if (isDelta()) return Color(0.0f);
  Vec3 wm;
  float etap;
  if (!halfVector(wo, wi, wm, etap)) return Color(0.0f);
  float cosO = cosTheta(wo), cosI = cosTheta(wi);
  float F = fresnelDielectric(dot(wo, wm), eta_);
  if (cosO * cosI > 0)
    return Color(dist_.D(wm) * dist_.G(wo, wi) * F / std::fabs(4.0f * cosI * cosO));
  float denom = dot(wi, wm) + dot(wo, wm) / etap;
  denom = denom * denom * cosI * cosO;
  float ft =
      dist_.D(wm) * (1.0f - F) * dist_.G(wo, wi) * std::fabs(dot(wi, wm) * dot(wo, wm) / denom);
  return tint_ * (ft / (etap * etap));
}

float DielectricLobe::pdf(const Vec3& wo, const Vec3& wi) const {
  if (isDelta()) return 0.0f;
  Vec3 wm;
  float etap;
  if (!halfVector(wo, wi, wm, etap)) return 0.0f;
  float R = fresnelDielectric(dot(wo, wm), eta_), T = 1.0f - R;
  if (cosTheta(wo) * cosTheta(wi) > 0)
    return dist_.visibleD(wo, wm) / (4.0f * std::fabs(dot(wo, wm))) * R;
  // Refraction's Jacobian dwm/dwi (Walter et al. eq. 17).
  float denom = dot(wi, wm) + dot(wo, wm) / etap;
  float dwmDwi = std::fabs(dot(wi, wm)) / (denom * denom);
  return dist_.visibleD(wo, wm) * dwmDwi * T;
}

BsdfSample DielectricLobe::sampleSmooth(const Vec3& wo, float uc) const {
  const DeltaSampleOf<Vec3> d = sampleSmoothDielectric(wo, eta_, tint_, uc);
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
  float R = fresnelDielectric(dot(wo, wm), eta_);
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

#include "materials/ggx_reflection.h"

#include "materials/fresnel.h"

namespace tray {

float GgxReflectionLobe::fresnelDielectricAbs(float cosI) const {
  // Reflection stays on the side it arrived from: the outside (the coat faces outwards).
  return fresnelDielectric(std::fabs(cosI), eta_);
}

Color GgxReflectionLobe::eval(const Vec3& wo, const Vec3& wi) const {
  return eval(terms(wo, wi));
}

float GgxReflectionLobe::pdf(const Vec3& wo, const Vec3& wi) const {
  return terms(wo, wi).pdf;
}

GgxReflectionLobe::Terms GgxReflectionLobe::terms(const Vec3& wo, const Vec3& wi) const {
  // f = F D G / (4 |cos_o cos_i|) with height-correlated G = 1 / ((1 + Lambda(wo)) +
  // Lambda(wi)), and pdf = D_wo(wm) / (4 |wo.wm|) (Walter et al. eq. 14) with the visible
  // normals' density D_wo = G1(wo) D |wo.wm| / |cos_o| (GgxDistribution::visibleD),
  // G1(wo) = 1 / (1 + Lambda(wo)): the two share the half vector, D and 1 + Lambda(wo).
  Terms t;
  if (isDelta() || !sameHemisphere(wo, wi)) return t;
  Vec3 wm = wi + wo;
  if (lengthSquared(wm) == 0) return t;
  wm = normalize(wm);
  if (wm.z < 0) wm = -wm;
  const float d = dist_.D(wm), onePlusLambdaO = 1.0f + dist_.lambda(wo);
  t.cosOM = dot(wo, wm);
  t.pdf = dist_.visibleD(wo, wm, d, onePlusLambdaO) / (4.0f * std::fabs(t.cosOM));
  const float cosO = absCosTheta(wo), cosI = absCosTheta(wi);
  if (cosO == 0 || cosI == 0) return t;
  t.scale = d * (1.0f / (onePlusLambdaO + dist_.lambda(wi))) / (4.0f * cosO * cosI);
  t.nonzero = true;
  return t;
}

bool GgxReflectionLobe::sampleDirection(const Vec3& wo, Vec2 u, Vec3& wi) const {
  // Sample visible normals on the upper side and mirror the answer for wo below.
  const Vec3 woUp = wo.z < 0 ? -wo : wo;
  const Vec3 wm = dist_.sampleVisibleNormal(woUp, u);
  wi = -woUp + 2.0f * dot(woUp, wm) * wm;
  if (wi.z <= 0) return false;  // shadowed by the microsurface: no sample (pbrt-v4 does the same)
  if (wo.z < 0) wi = -wi;
  return true;
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

#pragma once
#include <cmath>

#include "core/math.h"

namespace tray {

/// Exact unpolarised Fresnel reflectance of a dielectric interface (Born & Wolf; pbrt-v4
/// 9.3.2). cosI is the cosine with the normal on the incident side's +z; eta = n_t / n_i for
/// light arriving from +z. A negative cosI means arrival from the other side (eta inverted).
inline float fresnelDielectric(float cosI, float eta) {
  cosI = std::clamp(cosI, -1.0f, 1.0f);
  if (cosI < 0) {
    eta = 1.0f / eta;
    cosI = -cosI;
  }
  float sin2I = 1.0f - cosI * cosI;
  float sin2T = sin2I / (eta * eta);
  if (sin2T >= 1.0f) return 1.0f;  // total internal reflection
  float cosT = std::sqrt(std::max(0.0f, 1.0f - sin2T));
  float rParallel = (eta * cosI - cosT) / (eta * cosI + cosT);
  float rPerpendicular = (cosI - eta * cosT) / (cosI + eta * cosT);
  return (rParallel * rParallel + rPerpendicular * rPerpendicular) / 2.0f;
}

/// Schlick's approximation with a colored F0: glTF's metal Fresnel (glTF 2.0 spec, appendix B).
inline Color fresnelSchlick(const Color& f0, float cosI) {
  float m = std::clamp(1.0f - std::fabs(cosI), 0.0f, 1.0f);
  float m5 = (m * m) * (m * m) * m;
  return f0 + (Color(1.0f) - f0) * m5;
}

/// Refraction of w (pointing away from the surface) through normal n (+z side), eta = n_t /
/// n_i seen from +z (pbrt-v4 eq. 9.3 form). Returns false on total internal reflection;
/// etaRelative receives the eta actually used (inverted when w is below the surface).
inline bool refractDirection(const Vec3& w, Vec3 n, float eta, float& etaRelative, Vec3& wt) {
  float cosI = dot(n, w);
  if (cosI < 0) {
    eta = 1.0f / eta;
    cosI = -cosI;
    n = -n;
  }
  float sin2I = std::max(0.0f, 1.0f - cosI * cosI);
  float sin2T = sin2I / (eta * eta);
  if (sin2T >= 1.0f) return false;
  float cosT = std::sqrt(1.0f - sin2T);
  wt = -w / eta + (cosI / eta - cosT) * n;
  etaRelative = eta;
  return true;
}

}  // namespace tray

#pragma once
#include <cmath>

#include "core/math.h"
// fresnelDielectric and fresnelSchlick, written once for scalar code and the SIMD stages.
#include "materials/fresnel_lanes.h"

namespace tray {

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

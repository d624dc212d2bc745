#pragma once
// The Henyey-Greenstein phase function (Henyey & Greenstein 1941, "Diffuse radiation in the
// galaxy"), the scattering of TRay's homogeneous media (docs/subsurface.md), evaluated and
// sampled here only. Directions are directions of travel: cosTheta = dot(dIn, dOut) between
// the direction a path arrived along and the one it leaves along, so g > 0 scatters forward
// (pbrt-v4, Pharr et al. 2023, section 11.3.1, writes the same with wo reversed).
#include <algorithm>
#include <cmath>

#include "core/math.h"
#include "core/sampling.h"

namespace tray {

/// p(cosTheta) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cosTheta)^(3/2)), per steradian; it
/// integrates to 1 over the sphere and its mean cosine is g.
inline float henyeyGreenstein(float cosTheta, float g) {
  const float denom = 1.0f + g * g - 2.0f * g * cosTheta;
  return (1.0f - g * g) / (4.0f * kPi * denom * std::sqrt(std::max(denom, 1e-12f)));
}

/// A direction of travel after scattering from travel direction `dIn` (unit), drawn exactly
/// from the phase function by inverting its CDF in cosTheta (pbrt-v4 eq. 11.13); `pdf` is
/// henyeyGreenstein of the result, so the sample's weight p / pdf is 1.
inline Vec3 sampleHenyeyGreenstein(const Vec3& dIn, float g, Vec2 u, float& pdf) {
  float cosTheta;
  if (std::fabs(g) < 1e-3f) {
    cosTheta = 1.0f - 2.0f * u.x;
  } else {
    const float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u.x);
    cosTheta = (1.0f + g * g - s * s) / (2.0f * g);
  }
  cosTheta = std::clamp(cosTheta, -1.0f, 1.0f);
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  const float phi = 2.0f * kPi * u.y;
  const Vec3 local{sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
  pdf = henyeyGreenstein(cosTheta, g);
  return normalize(Frame::fromNormal(dIn).toWorld(local));
}

}  // namespace tray

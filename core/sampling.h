#pragma once
// Warping functions: uniform numbers in [0,1)^2 to directions and points, each with its pdf.
// Derivations in pbrt-v4 (Pharr, Jakob, Humphreys 2023), sections A.5 and 4.3.
#include <cmath>

#include "core/math.h"
// The warps, MIS and the frame, written once for scalar code and the SIMD stages.
#include "core/sampling_lanes.h"

namespace tray {

/// Uniform direction on the unit sphere; pdf = 1 / (4 pi).
inline Vec3 sampleUniformSphere(Vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  float phi = 2.0f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);

/// Uniform direction in the cone of half-angle acos(cosMax) about +z; pdf = 1 / (2 pi (1 -
/// cosMax)). For tiny cones 1 - cosMax cancels: pass it directly as oneMinusCosMax.
inline Vec3 sampleUniformCone(Vec2 u, float oneMinusCosMax) {
  float oneMinusCos = u.x * oneMinusCosMax;
  float cosTheta = 1.0f - oneMinusCos;
  float sinTheta = std::sqrt(std::max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
  float phi = 2.0f * kPi * u.y;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}
inline float uniformConePdf(float oneMinusCosMax) {
  return 1.0f / (2.0f * kPi * oneMinusCosMax);
}

/// The shading frame of scalar code.
using Frame = FrameOf<Vec3>;

}  // namespace tray

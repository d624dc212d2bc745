#pragma once
// The GGX (Trowbridge-Reitz) microfacet distribution with Smith height-correlated masking and
// sampling of visible normals. Walter et al. 2007, "Microfacet Models for Refraction through
// Rough Surfaces"; Heitz 2014, "Understanding the Masking-Shadowing Function"; Heitz 2018,
// "Sampling the GGX Distribution of Visible Normals". Local frame: +z is the mean normal.
#include "core/sampling.h"

namespace tray {

class GgxDistribution {
 public:
  /// alpha = roughness^2 (glTF's perceptual roughness squared, as glTF's BRDF appendix says).
  explicit GgxDistribution(float alpha) : alpha_(std::max(alpha, 1e-4f)) {}
  /// Below this the lobe is treated as a delta (mirror / perfect refraction): the GGX peak
  /// would overflow float and no sampler could find it.
  static constexpr float kSmoothAlpha = 1e-3f;
  bool effectivelySmooth() const { return alpha_ < kSmoothAlpha; }
  float alpha() const { return alpha_; }

  /// Microfacet normal density D(wm), projected-area normalised: integral D cos = 1.
  float D(const Vec3& wm) const {
    if (!(wm.z > 0)) return 0;  // microfacets face the upper side only
    float cos2 = wm.z * wm.z;
    float sin2 = std::max(0.0f, 1.0f - cos2);
    float a2 = alpha_ * alpha_;
    float e = cos2 + sin2 / a2;  // cos^2 (1 + tan^2 / a^2)
    return 1.0f / (kPi * a2 * e * e);
  }
  /// Smith's Lambda for GGX.
  float lambda(const Vec3& w) const {
    float cos2 = w.z * w.z;
    if (cos2 <= 0) return kInfinity;
    float tan2 = std::max(0.0f, 1.0f - cos2) / cos2;
    return (std::sqrt(1.0f + alpha_ * alpha_ * tan2) - 1.0f) / 2.0f;
  }
  float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  /// Height-correlated masking-shadowing.
  float G(const Vec3& wo, const Vec3& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
  /// Density of visible normals from direction w: G1(w) max(0, w.wm) D(wm) / cos(w).
  float visibleD(const Vec3& w, const Vec3& wm) const {
    if (w.z == 0) return 0;
    return visibleD(w, wm, D(wm), 1.0f + lambda(w));
  }
  /// The same from D(wm) and 1 + Lambda(w), for callers that have them already (the GGX
  /// reflection lobe's terms: its G shares 1 + Lambda(wo)).
  float visibleD(const Vec3& w, const Vec3& wm, float d, float onePlusLambda) const {
    float c = std::fabs(w.z);
    if (c == 0) return 0;
    return 1.0f / onePlusLambda / c * d * std::fabs(dot(w, wm));
  }
  /// Samples a visible microfacet normal from direction w (Heitz 2018, as in pbrt-v4 9.6.4).
  Vec3 sampleVisibleNormal(const Vec3& w, Vec2 u) const {
    Vec3 wh = normalize(Vec3(alpha_ * w.x, alpha_ * w.y, w.z));
    if (wh.z < 0) wh = -wh;
    Vec3 t1 = wh.z < 0.99999f ? normalize(cross(Vec3(0, 0, 1), wh)) : Vec3(1, 0, 0);
    Vec3 t2 = cross(wh, t1);
    Vec2 p = sampleUniformDiskPolar(u);
    float h = std::sqrt(std::max(0.0f, 1.0f - p.x * p.x));
    float s = (1.0f + wh.z) / 2.0f;
    p.y = (1.0f - s) * h + s * p.y;
    float pz = std::sqrt(std::max(0.0f, 1.0f - p.x * p.x - p.y * p.y));
    Vec3 nh = p.x * t1 + p.y * t2 + pz * wh;
    return normalize(Vec3(alpha_ * nh.x, alpha_ * nh.y, std::max(1e-6f, nh.z)));
  }

 private:
  float alpha_;
};

}  // namespace tray

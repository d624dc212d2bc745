#pragma once
// The GGX (Trowbridge-Reitz) microfacet distribution with Smith height-correlated masking and
// sampling of visible normals. Walter et al. 2007, "Microfacet Models for Refraction through
// Rough Surfaces"; Heitz 2014, "Understanding the Masking-Shadowing Function"; Heitz 2018,
// "Sampling the GGX Distribution of Visible Normals". Local frame: +z is the mean normal.
#include "core/sampling.h"
// The distribution's functions, written once for scalar code and the SIMD stages.
#include "materials/microfacet_lanes.h"

namespace tray {

class GgxDistribution {
 public:
  /// alpha = roughness^2 (glTF's perceptual roughness squared, as glTF's BRDF appendix says).
  explicit GgxDistribution(float alpha) : alpha_(ggxAlpha(alpha)) {}
  static constexpr float kSmoothAlpha = kGgxSmoothAlpha;
  bool effectivelySmooth() const { return alpha_ < kSmoothAlpha; }
  float alpha() const { return alpha_; }

  /// Microfacet normal density D(wm), projected-area normalised: integral D cos = 1.
  float D(const Vec3& wm) const { return ggxD(alpha_, wm); }
  /// Smith's Lambda for GGX.
  float lambda(const Vec3& w) const { return ggxLambda(alpha_, w); }
  float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  /// Height-correlated masking-shadowing.
  float G(const Vec3& wo, const Vec3& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
  /// Density of visible normals from direction w: G1(w) max(0, w.wm) D(wm) / cos(w).
  float visibleD(const Vec3& w, const Vec3& wm) const {
    if (w.z == 0) return 0;
    return ggxVisibleD(w, wm, D(wm), 1.0f + lambda(w));
  }
  /// Samples a visible microfacet normal from direction w (Heitz 2018, as in pbrt-v4 9.6.4).
  Vec3 sampleVisibleNormal(const Vec3& w, Vec2 u) const {
    return ggxSampleVisibleNormal(alpha_, w, u);
  }

 private:
  float alpha_;
};

}  // namespace tray

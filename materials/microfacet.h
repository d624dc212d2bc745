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
  explicit GgxDistribution(float alpha) : alpha_(ggxAlpha(alpha)), alphaY_(alpha_) {}
  /// Anisotropic (KHR_materials_anisotropy): alphaX along the local x axis (the frame's
  /// tangent), alphaY along y. Equal alphas give the isotropic distribution's exact floats.
  GgxDistribution(float alphaX, float alphaY)
      : alpha_(ggxAlpha(alphaX)), alphaY_(ggxAlpha(alphaY)) {}
  static constexpr float kSmoothAlpha = kGgxSmoothAlpha;
  /// Smooth only when both alphas are: a lobe stretched along one axis is not a mirror.
  bool effectivelySmooth() const { return alpha_ < kSmoothAlpha && alphaY_ < kSmoothAlpha; }
  /// alphaX (the isotropic alpha).
  float alpha() const { return alpha_; }
  float alphaY() const { return alphaY_; }
  bool anisotropic() const { return alpha_ != alphaY_; }

  /// Microfacet normal density D(wm), projected-area normalised: integral D cos = 1.
  float D(const Vec3& wm) const {
    return anisotropic() ? ggxDAniso(alpha_, alphaY_, wm) : ggxD(alpha_, wm);
  }
  /// Smith's Lambda for GGX.
  float lambda(const Vec3& w) const {
    return anisotropic() ? ggxLambdaAniso(alpha_, alphaY_, w) : ggxLambda(alpha_, w);
  }
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
    return ggxSampleVisibleNormalAniso(alpha_, alphaY_, w, u);
  }

 private:
  float alpha_, alphaY_;
};

}  // namespace tray

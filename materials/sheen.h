#pragma once
// KHR_materials_sheen's "Charlie" sheen BRDF (Conty Estevez & Kulla 2017, "Production Friendly
// Microfacet Sheen BRDF", SIGGRAPH course; the extension README's "Implementation Notes"):
//   f = sheenColor D(h) V(wo, wi),  D = (2 + 1/a) sin(theta_h)^(1/a) / (2 pi),
//   V = 1 / ((1 + Lambda(cos_o) + Lambda(cos_i)) 4 |cos_o cos_i|)
// with a = sheenRoughness and Lambda the paper's fitted exponential. Local frame, +z normal.
#include "materials/bsdf_sample.h"

namespace tray {

class CharlieSheen {
 public:
  /// Below this roughness D's exponent 1/a overflows float arithmetic; the extension's sample
  /// viewer and Filament clamp similarly.
  static constexpr float kMinRoughness = 0.07f;
  explicit CharlieSheen(float roughness) : a_(std::clamp(roughness, kMinRoughness, 1.0f)) {}
  /// f for sheenColor 1 (reflection only: same hemisphere).
  float eval(const Vec3& wo, const Vec3& wi) const;
  /// Directional albedo E(|cos_o|) = integral f |cos_i| dwi for sheenColor 1, from a table over
  /// (cos_o, roughness) integrated numerically once, at first use (sheen.cpp).
  float albedo(float cosO) const;
  float roughness() const { return a_; }

 private:
  float D(float cosH) const;
  float lambda(float cosTheta) const;
  float a_;
};

}  // namespace tray

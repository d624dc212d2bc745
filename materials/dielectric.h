#pragma once
#include "materials/bsdf_sample.h"
// sampleSmoothDielectric, written once for scalar code and the SIMD delta stage.
#include "materials/dielectric_lanes.h"
#include "materials/microfacet.h"

namespace tray {

/// A dielectric interface that reflects and refracts with exact Fresnel: rough (GGX, Walter et
/// al. 2007) or, below GgxDistribution::kSmoothAlpha, smooth (two delta lobes). eta = n_t / n_i
/// for light arriving from +z; the relative IOR of nested media comes from MediumStack.
/// Transmitted light is tinted by `tint` (glTF KHR_materials_transmission: base color) and
/// scaled by 1 / eta^2 (radiance is not invariant across a refractive boundary, Veach 1997
/// ch. 5.2).
class DielectricLobe {
 public:
  DielectricLobe(float alpha, float eta, const Color& tint)
      : dist_(alpha), eta_(eta), tint_(tint) {}
  /// Anisotropic roughness (KHR_materials_anisotropy applies to the BTDF too): alphaX along
  /// the local x axis.
  DielectricLobe(float alphaX, float alphaY, float eta, const Color& tint)
      : dist_(alphaX, alphaY), eta_(eta), tint_(tint) {}
  /// Index-matched interfaces pass light straight through: no scattering to see.
  bool isDelta() const { return eta_ == 1.0f || dist_.effectivelySmooth(); }
  float eta() const { return eta_; }
  Color eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  /// uc chooses reflection (uc < R / (R + T)) or refraction.
  BsdfSample sample(const Vec3& wo, float uc, Vec2 u) const;

 private:
  /// The generalised half vector of Walter et al. eq. 16, facing +z; false if degenerate or
  /// the microfacet is back-facing for either direction.
  bool halfVector(const Vec3& wo, const Vec3& wi, Vec3& wm, float& etap) const;
  BsdfSample sampleSmooth(const Vec3& wo, float uc) const;
  GgxDistribution dist_;
  float eta_;
  Color tint_;
};

}  // namespace tray

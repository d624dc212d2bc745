#pragma once
#include <algorithm>

#include "materials/bsdf_sample.h"
// sampleSmoothDielectric, written once for scalar code and the SIMD delta stage.
#include "materials/dielectric_lanes.h"
#include "materials/iridescence.h"
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
  /// KHR_materials_iridescence on glass: a thin film (IOR filmIor, thicknessNm nanometres) on
  /// the outside whose reflectance (materials/iridescence.h) is mixed with the plain Fresnel by
  /// `factor`; what it does not reflect is transmitted, channel by channel, as the reference
  /// viewer's fresnel_mix weighs transmission by 1 - F. A factor or thickness of 0 leaves the
  /// lobe exactly as it was.
  void setIridescence(float factor, float filmIor, float thicknessNm) {
    if (!iridescenceApplies(factor, thicknessNm)) return;
    irid_ = std::min(factor, 1.0f), filmIor_ = filmIor, filmNm_ = thicknessNm;
  }
  bool iridescent() const { return irid_ > 0; }
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
  /// eval's two lobes for a reflectance F: a float (exact Fresnel) or a colour (the film's).
  template <class R>
  Color evalWith(const Vec3& wo, const Vec3& wi, const Vec3& wm, float etap, const R& F) const;
  /// The film-and-plain reflectance at a microfacet cosine (negative: wo inside), given the
  /// plain Fresnel there.
  Color filmFresnel(float cosI, float plain) const;
  /// The probability of sampling reflection at that cosine: the plain Fresnel, or the mean of
  /// the film's colour.
  float reflectChoice(float cosI) const;
  GgxDistribution dist_;
  float eta_;
  Color tint_;
  float irid_ = 0, filmIor_ = 1.3f, filmNm_ = 0;  ///< KHR_materials_iridescence (0: off)
};

}  // namespace tray

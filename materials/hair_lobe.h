#pragma once
#include <array>

#include "core/math.h"
#include "materials/bsdf_sample.h"

namespace tray {

/// Chiang, Bitterli, Tappan & Burley 2016, "A Practical and Controllable Hair and Fur Model for
/// Production Path Tracing" (as pbrt-v4 9.9's HairBxDF): a dielectric cylinder seen at offset
/// h in [-1, 1] across its width, with lobes p = 0 (R), 1 (TT), 2 (TRT) and a residual lobe for
/// p >= 3. Each lobe is a longitudinal term M_p (d'Eon et al. 2011, variance from the
/// longitudinal roughness beta_m), an attenuation A_p (Fresnel and the absorption sigma_a along
/// the internal path) and an azimuthal term N_p (a trimmed logistic of scale s from the
/// azimuthal roughness beta_n, centred on the specular azimuth Phi(p, h)).
///
/// Local frame (pbrt-v4's): x along the fibre, y and z span the normal plane; a direction's
/// sin(theta) is w.x and its azimuth phi = atan2(w.z, w.y). Unlike pbrt, eval returns f times
/// the projected cosine of wi (pbrt divides its sum by |cos| to the shading normal only to have
/// the integrator multiply it back): HairBsdf divides by its own normal's cosine.
class HairLobe {
 public:
  static constexpr int kPMax = 3;
  /// alphaDegrees: the cuticle scales' tilt, which shifts the lobes' longitudinal peaks
  /// (Marschner et al. 2003; Chiang et al. 2016, section 4.1).
  HairLobe(float h, float eta, const Color& sigmaA, float betaM, float betaN, float alphaDegrees);
  /// f(wo, wi) |cos theta_wi|: the sum of the lobes, per unit solid angle of wi.
  Color evalProjected(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  /// uc picks the lobe (then is reused for the azimuth), u the longitudinal angle; wi in the
  /// local frame, f is evalProjected's value (BsdfSample::f here already includes the cosine).
  BsdfSample sample(const Vec3& wo, float uc, Vec2 u) const;

  /// sigma_a from eumelanin and pheomelanin concentrations (Chiang et al. 2016, section 4.2,
  /// d'Eon et al. 2011's absorption coefficients).
  static Color sigmaAFromConcentration(float eumelanin, float pheomelanin);
  /// sigma_a that gives multiple-scattered colour c at azimuthal roughness betaN (Chiang et al.
  /// 2016, equation 9).
  static Color sigmaAFromReflectance(const Color& c, float betaN);

 private:
  std::array<Color, kPMax + 1> attenuation(float cosThetaO, const Color& T) const;
  std::array<float, kPMax + 1> lobePdf(float cosThetaO) const;
  /// sin and cos of theta_o tilted by the cuticle angle for lobe p (pbrt-v4 9.9.3's
  /// "Compute sin theta_o and cos theta_o terms accounting for scales").
  void tilted(int p, float sinThetaO, float cosThetaO, float& sinP, float& cosP) const;
  float h_, gammaO_, eta_;
  Color sigmaA_;
  float v_[kPMax + 1];  ///< longitudinal variance per lobe
  float s_;             ///< azimuthal logistic scale
  float sin2kAlpha_[3], cos2kAlpha_[3];
};

}  // namespace tray

#pragma once
// KHR_materials_sheen over the metallic-roughness base, by the albedo scaling of Conty Estevez
// & Kulla 2017 as the extension README ("Sheen layering") gives it:
//   f = sheenColor f_charlie + f_base min(1 - s E(cos_o), 1 - s E(cos_i)),  s = max(sheenColor)
// where E is the Charlie BRDF's directional albedo (materials/sheen.cpp). The sheen reflects
// at most s E(cos_o) and the base keeps at most 1 - s E(cos_o): energy is conserved, and the
// min of both directions keeps the base term symmetric. A layer of Bsdf (materials/
// bsdf_layer.h), under the clearcoat if there is one.
#include <algorithm>

#include "core/material.h"
#include "core/sampling.h"
#include "materials/bsdf_layer.h"
#include "materials/bsdf_sample.h"
#include "materials/sheen.h"

namespace tray {

class SheenLayer {
 public:
  /// As for the clearcoat: the base's share of sampling never drops to 0.
  static constexpr float kMinBaseEstimate = 0.05f;

  static bool applies(const ShadingMaterial& m) { return !isBlack(m.sheenColor); }
  SheenLayer(const ShadingMaterial& m, const Frame& base)
      : color_(max(m.sheenColor, Color(0.0f))),
        max_(std::min(maxComponent(color_), 1.0f)),
        lobe_(m.sheenRoughness),
        baseEstimate_(std::clamp(maxComponent(m.baseColor), kMinBaseEstimate, 1.0f)),
        frame_(base) {}
  bool isDelta() const { return false; }

  /// sEo = s E(cos_o), what the sheen reflects of light from wo at most, and the sheen's share
  /// of sampling: its share of the reflected energy against the base's.
  struct At {
    float sEo, probability;
  };
  At at(const Vec3& wo) const {
    const float sEo = max_ * lobe_.albedo(dot(wo, frame_.n));
    const float base = (1.0f - sEo) * baseEstimate_;
    return {sEo, sEo > 0 ? sEo / (sEo + base) : 0.0f};
  }
  Color eval(const Vec3& wo, const Vec3& wi, float& pdf, uint8_t kinds) const {
    const Vec3 woL = frame_.toLocal(wo), wiL = frame_.toLocal(wi);
    pdf = sameHemisphere(woL, wiL) ? cosineHemispherePdf(absCosTheta(wiL)) : 0.0f;
    return (kinds & kDiffuseLobes) ? color_ * lobe_.eval(woL, wiL) : Color(0.0f);
  }
  float baseScale(const At& a, const Vec3& wi) const {
    const float sEi = max_ * lobe_.albedo(dot(wi, frame_.n));
    return std::min(1.0f - a.sEo, 1.0f - sEi);
  }
  /// The sheen lobe is broad: cosine-weighted directions on wo's side.
  BsdfSample sample(const Vec3& wo, Vec2 u) const {
    BsdfSample s;
    const float cosO = dot(wo, frame_.n);
    if (cosO == 0) return s;
    Vec3 wi = sampleCosineHemisphere(u);
    wi.z = cosO < 0 ? -wi.z : wi.z;
    s.wi = frame_.toWorld(wi);
    s.pdf = cosineHemispherePdf(std::fabs(wi.z));
    return s;
  }

 private:
  Color color_;
  float max_;  ///< max component of color_: the albedo scaling's weight
  CharlieSheen lobe_;
  float baseEstimate_;
  Frame frame_;
};

}  // namespace tray

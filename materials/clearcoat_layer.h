#pragma once
// KHR_materials_clearcoat: a smooth or GGX-rough dielectric coat over the whole material, as the
// extension's README ("Implementation") layers it:
//   f = c fc(wo, wi) + (1 - c Fc(cos_o)) f_base(wo, wi)
// with fc the coat's microfacet BRDF (exact dielectric Fresnel, IOR 1.5, i.e. F0 = 0.04), Fc
// its Fresnel seen from wo, and c = clearcoat. Light the coat reflects is taken from the base
// (the weight 1 - c Fc); the coat itself absorbs nothing. The coat has its own normal: the
// interpolated one, or clearcoatNormalTexture's. A layer of Bsdf (materials/bsdf_layer.h).
#include <algorithm>
#include <cmath>

#include "core/material.h"
#include "core/sampling.h"
#include "materials/bsdf_layer.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/ggx_reflection.h"

namespace tray {

class ClearcoatLayer {
 public:
  /// The extension's coat: IOR 1.5 against air.
  static constexpr float kIor = 1.5f;
  /// The base's share of sampling is at least this estimate of its albedo: a black base still
  /// gets samples (its lobes may be bright at other angles).
  static constexpr float kMinBaseEstimate = 0.05f;

  static bool applies(const ShadingMaterial& m) { return m.clearcoat > 0; }
  ClearcoatLayer(const ShadingMaterial& m, const Frame& base)
      : clearcoat_(std::clamp(m.clearcoat, 0.0f, 1.0f)),
        lobe_(coatLobe(m.clearcoatRoughness)),
        baseN_(base.n),
        // How much the base reflects, roughly: its colour (metals, diffuse and glass all scale
        // with it). Only the sampling choice depends on it.
        baseEstimate_(std::clamp(maxComponent(m.baseColor), kMinBaseEstimate, 1.0f)) {
    // The coat's normal on the side of the base's frame (the side wo arrives from).
    Vec3 n = m.clearcoatN;
    const float len = length(n);
    if (!(len > 0) || !std::isfinite(len)) n = base.n;
    if (dot(n, base.n) < 0) n = -n;
    ownFrame_ = !(n == base.n) && !(-n == base.n);
    frame_ = ownFrame_ ? Frame::fromNormal(normalize(n)) : base;
  }
  bool isDelta() const { return lobe_.isDelta(); }

  /// cFc = c Fc(wo), the coat's reflectance seen from wo, and the coat's share of sampling:
  /// c Fc against (1 - c Fc) x the base's albedo estimate (any choice in (0, 1) is unbiased).
  struct At {
    float cFc, probability;
  };
  At at(const Vec3& wo) const {
    const float cFc = clearcoat_ * fresnelDielectric(std::fabs(dot(wo, frame_.n)), kIor);
    const float base = (1.0f - cFc) * baseEstimate_;
    return {cFc, cFc > 0 ? cFc / (cFc + base) : 0.0f};
  }
  Color eval(const Vec3& wo, const Vec3& wi, float& pdf, uint8_t kinds) const {
    const Vec3 woC = frame_.toLocal(wo), wiC = frame_.toLocal(wi);
    const GgxReflectionLobe::Terms terms = lobe_.terms(woC, wiC);  // its eval and pdf
    pdf = terms.pdf;
    Color coat = (kinds & kSpecularLobes) ? lobe_.eval(terms) * clearcoat_ : Color(0.0f);
    // The integrator multiplies by the base normal's cosine; the coat's BRDF goes with its own.
    if (ownFrame_ && !isBlack(coat)) {
      const float cosBase = std::fabs(dot(wi, baseN_));
      coat *= cosBase > 0 ? absCosTheta(wiC) / cosBase : 0.0f;
    }
    return coat;
  }
  float baseScale(const At& a, const Vec3&) const { return 1.0f - a.cFc; }
  BsdfSample sample(const Vec3& wo, Vec2 u) const {
    BsdfSample s = lobe_.sample(frame_.toLocal(wo), u);
    if (!s.valid()) return s;
    s.wi = frame_.toWorld(s.wi);
    if (s.delta) {
      // The mirror's coefficient F / |cos_coat| becomes c F / |cos_base| (the integrator
      // multiplies by the base normal's cosine).
      const float cosBase = std::fabs(dot(s.wi, baseN_));
      if (!(cosBase > 0)) return BsdfSample{};
      s.f *= clearcoat_ * (absCosTheta(frame_.toLocal(s.wi)) / cosBase);
    }
    return s;
  }

 private:
  static GgxReflectionLobe coatLobe(float roughness) {
    const float r = std::clamp(roughness, 0.0f, 1.0f);
    return GgxReflectionLobe::dielectric(r * r, kIor);
  }
  float clearcoat_;
  GgxReflectionLobe lobe_;
  Vec3 baseN_;
  float baseEstimate_;
  Frame frame_;
  bool ownFrame_;  ///< the coat's normal differs from the base's
};

}  // namespace tray

#include "materials/bsdf.h"

#include "materials/fresnel.h"

namespace tray {

void Bsdf::initLobes(const ShadingMaterial& m, float eta) {
  lambertOnly_ = false;
  probCached_ = false;
  const GgxMixtureOf<Vec3> x = ggxMixture(m.metallic, m.transmission, m.roughness, m.baseColor);
  wMetal_ = x.wMetal, wGlass_ = x.wGlass, wPlastic_ = x.wPlastic, coat_ = x.coat;
  const float alpha = m.roughness * m.roughness;
  coatTinted_ = m.specular != 1.0f || !(m.specularColor == Color(1.0f));
  metal_.value = GgxReflectionLobe::metal(alpha, m.baseColor);
  coatLobe_.value = coatTinted_
                        ? GgxReflectionLobe::dielectric(alpha, eta, m.specular, m.specularColor)
                        : GgxReflectionLobe::dielectric(alpha, eta);
  glass_.value = DielectricLobe(alpha, eta, m.baseColor);
  // KHR_materials_anisotropy (README, "Implementation"): alpha_t = mix(alpha, 1, strength^2)
  // along the direction, alpha_b = alpha across it.
  const float strength = std::min(m.anisotropy, 1.0f);
  const float alphaT = alpha + (1.0f - alpha) * strength * strength;
  const bool anisotropic = m.anisotropy > 0 && ggxAlpha(alphaT) != ggxAlpha(alpha);
  if (anisotropic) {
    frame_ = anisotropicFrame(frame_.n, m.anisotropyDirection);
    metal_.value = GgxReflectionLobe::anisotropic(metal_.value, alphaT, alpha);
    coatLobe_.value = GgxReflectionLobe::anisotropic(coatLobe_.value, alphaT, alpha);
    glass_.value = DielectricLobe(alphaT, alpha, eta, m.baseColor);
  }
  // KHR_materials_diffuse_transmission (README, "Implementation"): the diffuse base is
  // mix(diffuse_brdf(baseColor), diffuse_btdf(colour), dt).
  diffuseTransmits_ = m.diffuseTransmission > 0;
  if (diffuseTransmits_) {
    const float dt = std::min(m.diffuseTransmission, 1.0f);
    dtLobe_.value =
        DiffuseTransmissionLobe((1.0f - dt) * m.baseColor, dt * m.diffuseTransmissionColor);
    diffuse_.albedo = dtLobe_->reflect() + dtLobe_->transmit();
  }
  scalarMix_ = anisotropic || diffuseTransmits_;
  // KHR_materials_iridescence: a thin film over the metal, the coat and the glass.
  iridescent_ = iridescenceApplies(m.iridescence, m.iridescenceThickness);
  if (iridescent_) {
    metal_->setIridescence(m.iridescence, m.iridescenceIor, m.iridescenceThickness);
    coatLobe_->setIridescence(m.iridescence, m.iridescenceIor, m.iridescenceThickness);
    glass_->setIridescence(m.iridescence, m.iridescenceIor, m.iridescenceThickness);
    coatTinted_ = true;  // the coat's Fresnel is the lobe's: coatFresnel reads it
  }
  layers_.init(m, frame_);
  hasNonDelta_ =
      (wMetal_ > 0 && !metal_->isDelta()) || (wGlass_ > 0 && !glass_->isDelta()) ||
      (wPlastic_ > 0 && (!isBlack(diffuse_.albedo) || (coat_ > 0 && !coatLobe_->isDelta())));
  // Lobes that can scatter at all (probabilities() gives the others probability 0). The
  // albedo test is maxComponent > 0 spelled without std::max, whose branches depend on the
  // colour and are mispredicted when the material changes between bounces (callgrind
  // --branch-sim: 13% of the Cornell box's mispredictions).
  const Color& a = diffuse_.albedo;
  const bool metal = wMetal_ > 0, glass = wGlass_ > 0, coat = wPlastic_ > 0 && coat_ > 0,
             diffuse = wPlastic_ > 0 && (a.x > 0 || a.y > 0 || a.z > 0);
  const int active = metal + glass + coat + diffuse;
  // A lone lobe's weight is exactly 1 here: wMetal_ = 1, wGlass_ = 1, or wPlastic_ = 1 with
  // no coat, so that 1 - coatFresnel = 1.
  only_ = active == 0                 ? Only::kNothing
          : active > 1                ? Only::kMixture
          : metal && wMetal_ == 1     ? Only::kMetal
          : glass && wGlass_ == 1     ? Only::kGlass
          : diffuse && wPlastic_ == 1 ? Only::kDiffuse
                                      : Only::kMixture;
  // kDiffuse's shortcuts are Lambert reflection's alone.
  if (only_ == Only::kDiffuse && diffuseTransmits_) only_ = Only::kMixture;
}

Frame Bsdf::anisotropicFrame(const Vec3& n, const Vec3& direction) {
  Frame f = Frame::fromNormal(n);
  const Vec3 t = direction - n * dot(n, direction);
  const float len = length(t);
  if (!(len > 1e-6f) || !std::isfinite(len)) return f;
  f.t = t / len;
  f.b = cross(n, f.t);  // t x b = n, as fromNormal's basis
  return f;
}

Color Bsdf::diffuseEval(const Vec3& wo, const Vec3& wi) const {
  if (!diffuseTransmits_) return includes(kDiffuseLobes) ? diffuse_.eval(wo, wi) : Color(0.0f);
  // The transmitted half counts as transmission for the light-path AOVs (evalLobes).
  if (!includes(sameHemisphere(wo, wi) ? kDiffuseLobes : kTransmissionLobes)) return Color(0.0f);
  return dtLobe_->eval(wo, wi);
}

void Bsdf::initHair(const HairParams& p, const Vec3& tangent, const Vec3& n) {
  wMetal_ = wGlass_ = wPlastic_ = coat_ = 0;
  coatTinted_ = false;
  hasNonDelta_ = true;
  lambertOnly_ = false;
  probCached_ = false;
  // Read by transmits() and the mixture paths, which the hair lobe never takes: set, not left
  // unbuilt (valgrind saw transmits() read diffuseTransmits_ uninitialised on the fur scene).
  scalarMix_ = false, diffuseTransmits_ = false, iridescent_ = false;
  only_ = Only::kHair;
  new (&hair_.value) HairBsdf(p, tangent, n);
}

bool Bsdf::isGgxMixture(const ShadingMaterial& m) {
  if (m.hair) return false;
  if (!std::isfinite(m.metallic) || !std::isfinite(m.roughness) || !(m.transmission <= 0) ||
      BsdfLayers::anyApplies(m) || m.specular != 1.0f || m.anisotropy > 0 ||
      m.diffuseTransmission > 0 ||
      iridescenceApplies(m.iridescence, m.iridescenceThickness) ||  // scalar: the film
      !(m.specularColor == Color(1.0f)) || isLambertOnly(m))
    return false;
  const GgxMixtureOf<Vec3> x = ggxMixture(m.metallic, 0.0f, m.roughness, m.baseColor);
  const Color& a = m.baseColor;
  const bool lambert = x.wPlastic > 0 && (a.x > 0 || a.y > 0 || a.z > 0);
  // Mirrors (delta metal and coat) with a Lambert lobe beside them: the stage's light sample is
  // the Lambert lobe's. Without one every lobe is a delta: no light sample, not this stage.
  if (x.ggxDelta) return lambert;
  return x.metalOn || lambert || (x.wPlastic > 0 && x.coat > 0);
}

bool Bsdf::isSmoothGlass(const ShadingMaterial& m) {
  if (m.hair) return false;
  if (!std::isfinite(m.metallic) || !std::isfinite(m.roughness) || !std::isfinite(m.transmission) ||
      BsdfLayers::anyApplies(m) || m.anisotropy > 0 || m.diffuseTransmission > 0 ||
      iridescenceApplies(m.iridescence, m.iridescenceThickness))  // scalar: the film
    return false;
  const GgxMixtureOf<Vec3> x = ggxMixture(m.metallic, m.transmission, m.roughness, m.baseColor);
  // initLobes' Only::kGlass: a glass weight (1 - wMetal) t of exactly 1 needs wMetal 0 and t 1,
  // which leaves wPlastic = 0: no metal, coat or Lambert lobe beside it.
  return x.wGlass == 1 && x.ggxDelta;
}

GgxMixtureOf<Vec3> Bsdf::mixture() const {
  const bool specular = includes(kSpecularLobes);
  GgxMixtureOf<Vec3> x;
  x.wMetal = wMetal_, x.wGlass = wGlass_, x.wPlastic = wPlastic_, x.coat = coat_;
  x.alpha = metal_->alpha();
  x.albedo = diffuse_.albedo;
  x.metalOn = wMetal_ > 0 && specular;
  x.glassOn = wGlass_ > 0;  // eval passes the glass lobe's value only where includesGlass
  x.coatOn = wPlastic_ > 0 && coat_ > 0 && specular;
  x.diffuseOn = wPlastic_ > 0 && includes(kDiffuseLobes);
  x.ggxDelta = metal_->isDelta();
  return x;
}

float Bsdf::coatFresnel(const Vec3& wo) const {
  if (coatTinted_) return coat_ > 0 ? coat_ * maxComponent(coatLobe_->fresnel(wo.z)) : 0.0f;
  return coatFresnelOf(coat_, wo.z, coatEta_);
}

Bsdf::Probabilities Bsdf::computeProbabilities(const Vec3& wo) const {
  // diffuse_.albedo is reflect + transmit with diffuse transmission: the lobe's share.
  return mixtureProbabilities(mixture(), coatFresnel(wo));
}

Color Bsdf::evalLocal(const Vec3& wo, const Vec3& wi) const {
  switch (only_) {
    case Only::kMetal:
      return metal_->eval(wo, wi);
    case Only::kGlass:
      return glass_->eval(wo, wi);
    case Only::kDiffuse:
      return diffuse_.eval(wo, wi);
    case Only::kHair: {  // world space (materials/hair_bsdf.h)
      float unused;
      return hair_->eval(frame_.toWorld(wo), frame_.toWorld(wi), unused);
    }
    case Only::kNothing:
    case Only::kMixture:
      break;
  }
  Color f(0.0f);
  if (wMetal_ > 0 && includes(kSpecularLobes)) f += wMetal_ * metal_->eval(wo, wi);
  if (wGlass_ > 0 && includesGlass(wo, wi)) f += wGlass_ * glass_->eval(wo, wi);
  if (wPlastic_ > 0) {
    if (coat_ > 0 && includes(kSpecularLobes)) f += (wPlastic_ * coat_) * coatLobe_->eval(wo, wi);
    if (includes(kDiffuseLobes) || diffuseTransmits_)
      f += (wPlastic_ * (1.0f - coatFresnel(wo))) * diffuseEval(wo, wi);
  }
  return f;
}

float Bsdf::pdfLocal(const Vec3& wo, const Vec3& wi) const {
  switch (only_) {
    case Only::kMetal:
      return metal_->pdf(wo, wi);
    case Only::kGlass:
      return glass_->pdf(wo, wi);
    case Only::kDiffuse:
      return diffuse_.pdf(wo, wi);
    case Only::kHair: {
      float pdf;
      hair_->eval(frame_.toWorld(wo), frame_.toWorld(wi), pdf);
      return pdf;
    }
    case Only::kNothing:
      return 0.0f;
    case Only::kMixture:
      break;
  }
  const Probabilities& p = probabilities(wo);
  float pdf = 0;
  if (p.metal > 0) pdf += p.metal * metal_->pdf(wo, wi);
  if (p.glass > 0) pdf += p.glass * glass_->pdf(wo, wi);
  if (p.coat > 0) pdf += p.coat * coatLobe_->pdf(wo, wi);
  if (p.diffuse > 0) pdf += p.diffuse * diffusePdf(wo, wi);
  return pdf;
}

Color Bsdf::mixtureEvalPdf(const Vec3& wo, const Vec3& wi, const Probabilities& p, float& pdf,
                           float& ggxPdf) const {
  if (iridescent_)
    return tray::mixtureEvalPdf(mixture(), p, wo, wi, coatFresnelAt(), glassAt(p), pdf, ggxPdf,
                                metalFresnelAt());
  return tray::mixtureEvalPdf(mixture(), p, wo, wi, coatFresnelAt(), glassAt(p), pdf, ggxPdf);
}

BsdfSample Bsdf::sampleLocal(const Vec3& wo, float uc, Vec2 u) const {
  if (only_ == Only::kHair) {  // world space (materials/hair_bsdf.h), back to the local frame
    BsdfSample s = hair_->sample(frame_.toWorld(wo), uc, u);
    s.wi = frame_.toLocal(s.wi);
    return s;
  }
  // A lone lobe takes uc whole; a mixture picks a lobe with uc, then rescales uc to [0,1) for
  // the lobe's own discrete choice. -1: no lobe.
  int lobe = only_ == Only::kMetal     ? 0
             : only_ == Only::kGlass   ? 1
             : only_ == Only::kDiffuse ? 3
                                       : -1;
  float prob = 1.0f, ucLobe = uc;
  if (only_ == Only::kMixture) {
    const Probabilities& p = probabilities(wo);
    const float cdf[4] = {p.metal, p.metal + p.glass, p.metal + p.glass + p.coat, 1.0f};
    lobe = 0;
    while (lobe < 3 && uc >= cdf[lobe]) ++lobe;
    const float probs[4] = {p.metal, p.glass, p.coat, p.diffuse};
    prob = probs[lobe];
    const float lo = lobe == 0 ? 0.0f : cdf[lobe - 1];
    if (prob > 0) ucLobe = std::min((uc - lo) / prob, 0.99999994f);
    // Metal, coat and Lambert (mirrors too): the one-text sample, which evaluates only the
    // mixture (a rough GGX lobe's own f and pdf would only be thrown away for the mixture's:
    // the spheres scene spent ~1/3 of the BSDF's instructions on them, callgrind).
    if (lobe != 1 && !scalarMix_) {
      const MixtureSampleOf<Vec3> m =
          iridescent_ ? mixtureSample(mixture(), p, wo, uc, u, coatFresnelAt(), glassAt(p),
                                      metalFresnelAt())
                      : mixtureSample(mixture(), p, wo, uc, u, coatFresnelAt(), glassAt(p));
      BsdfSample s;
      s.wi = m.wi, s.f = m.f, s.pdf = m.pdf;
      s.delta = m.delta;
      return s;
    }
  }
  // The lobe's sample is built in place in the result (returned prvalues, then one named
  // variable): assigning it from a returned temporary cost a store-forwarding stall per sample
  // (see setSpawnRay in core/ray.h).
  const auto lobeSample = [&]() -> BsdfSample {
    switch (lobe) {
      case 0:
        return metal_->sample(wo, u);
      case 1:
        return glass_->sample(wo, ucLobe, u);
      case 2:
        return coatLobe_->sample(wo, u);
      case 3:
        return diffuseTransmits_ ? dtLobe_->sample(wo, ucLobe, u) : diffuse_.sample(wo, u);
      default:
        return BsdfSample{};
    }
  };
  BsdfSample s = prob > 0 ? lobeSample() : BsdfSample{};
  // A lone lobe: its own sample, whose f and pdf are its eval and pdf.
  const bool lone = only_ != Only::kMixture;
  if (lone || !s.valid()) {
    if (lone && (!(s.pdf > 0) || !std::isfinite(s.pdf))) s.pdf = 0;
    return s;
  }
  if (s.delta) {  // a discrete choice among delta and continuous lobes: probability x pdf
    const float weights[4] = {wMetal_, wGlass_, wPlastic_ * coat_, 1.0f};
    s.f *= weights[lobe];
    s.pdf *= prob;
    return s;
  }
  if (scalarMix_) {
    s.f = evalLocal(wo, s.wi);
    s.pdf = pdfLocal(wo, s.wi);
  } else {
    float unused;
    s.f = mixtureEvalPdf(wo, s.wi, probabilities(wo), s.pdf, unused);
  }
  if (!(s.pdf > 0) || !std::isfinite(s.pdf)) s.pdf = 0;
  return s;
}

Color Bsdf::eval(const Vec3& wo, const Vec3& wi) const {
  float unused;
  if (only_ == Only::kHair) return hair_->eval(wo, wi, unused);
  if (layers_.any()) return eval(wo, wi, unused);
  return evalLocal(frame_.toLocal(wo), frame_.toLocal(wi));
}

float Bsdf::pdf(const Vec3& wo, const Vec3& wi) const {
  float p;
  if (only_ == Only::kHair) return hair_->eval(wo, wi, p), p;
  if (layers_.any()) return eval(wo, wi, p), p;
  return pdfLocal(frame_.toLocal(wo), frame_.toLocal(wi));
}

template <size_t I>
Color Bsdf::evalFrom(const Vec3& wo, const Vec3& wi, float& pdf) const {
  if constexpr (I == BsdfLayers::kCount) {
    return baseEval(wo, wi, pdf);
  } else {
    if (!layers_.on<I>()) return evalFrom<I + 1>(wo, wi, pdf);
    const auto& layer = layers_.get<I>();
    const auto at = layer.at(wo);
    float layerPdf, belowPdf;
    const Color f = layer.eval(wo, wi, layerPdf, lobeMask_);
    const Color below = evalFrom<I + 1>(wo, wi, belowPdf);
    pdf = at.probability * layerPdf + (1.0f - at.probability) * belowPdf;
    return f + below * layer.baseScale(at, wi);
  }
}

template <size_t I>
BsdfSample Bsdf::sampleFrom(const Vec3& wo, float uc, Vec2 u) const {
  if constexpr (I == BsdfLayers::kCount) {
    return baseSample(wo, uc, u);
  } else {
    if (!layers_.on<I>()) return sampleFrom<I + 1>(wo, uc, u);
    const auto& layer = layers_.get<I>();
    const auto at = layer.at(wo);
    BsdfSample s;
    if (uc < at.probability) {
      s = layer.sample(wo, u);
      if (!s.valid()) return s;
      if (s.delta) {  // the layer's mirror, chosen with its probability
        s.pdf *= at.probability;
        return s;
      }
    } else {
      const float ucBelow = std::min((uc - at.probability) / (1.0f - at.probability), 0.99999994f);
      s = sampleFrom<I + 1>(wo, ucBelow, u);
      if (!s.valid()) return s;
      if (s.delta) {  // a delta lobe below, weighted as eval weighs what lies below
        s.f *= layer.baseScale(at, s.wi);
        s.pdf *= 1.0f - at.probability;
        return s;
      }
    }
    // A continuous direction: the value and density of this layer and all below it (each lobe
    // could have given it).
    s.f = evalFrom<I>(wo, s.wi, s.pdf);
    if (!(s.pdf > 0) || !std::isfinite(s.pdf)) s.pdf = 0;
    return s;
  }
}

Color Bsdf::layersEval(const Vec3& wo, const Vec3& wi, float& pdf) const {
  if (only_ == Only::kHair) return hair_->eval(wo, wi, pdf);
  return evalFrom<0>(wo, wi, pdf);
}

BsdfSample Bsdf::layersSample(const Vec3& wo, float uc, Vec2 u) const {
  if (only_ == Only::kHair) return hair_->sample(wo, uc, u);
  return sampleFrom<0>(wo, uc, u);
}

Color Bsdf::baseEval(const Vec3& wo, const Vec3& wi, float& pdf) const {
  // Lambert needs only the cosines: skip the tangent axes
  if (only_ == Only::kDiffuse) return lambertEval(wo, wi, pdf);
  const Vec3 woLocal = frame_.toLocal(wo), wiLocal = frame_.toLocal(wi);
  // Metal and mixtures: eval and pdf share their GGX terms and probabilities().
  if (only_ == Only::kMetal) {
    const GgxReflectionLobe::Terms t = metal_->terms(woLocal, wiLocal);
    pdf = t.pdf;
    return metal_->eval(t);
  }
  if (only_ == Only::kMixture && !scalarMix_) {
    float unused;
    return mixtureEvalPdf(woLocal, wiLocal, probabilities(woLocal), pdf, unused);
  }
  pdf = pdfLocal(woLocal, wiLocal);
  return evalLocal(woLocal, wiLocal);
}

BsdfSample Bsdf::baseSample(const Vec3& wo, float uc, Vec2 u) const {
  // Lambert reads only the side of wo (its local z): skip the tangent axes.
  if (only_ == Only::kDiffuse) return lambertSample(wo, u);
  BsdfSample s = sampleLocal(frame_.toLocal(wo), uc, u);
  s.wi = frame_.toWorld(s.wi);
  return s;
}

LobeSplit Bsdf::evalLobes(const Vec3& wo, const Vec3& wi) const {
  // The same sums as eval, one kind of lobe at a time (the lone-lobe shortcuts skip the masks).
  if (only_ == Only::kHair) {
    // Light-path AOVs: the fibre's lobes count as diffuse (R, TT and TRT are all rough).
    LobeSplit out;
    out.diffuse = eval(wo, wi);
    return out;
  }
  Bsdf part = *this;
  part.only_ = only_ == Only::kNothing ? Only::kNothing : Only::kMixture;
  part.lambertOnly_ = false;
  LobeSplit out;
  part.lobeMask_ = kDiffuseLobes;
  out.diffuse = part.eval(wo, wi);
  part.lobeMask_ = kSpecularLobes;
  out.specular = part.eval(wo, wi);
  part.lobeMask_ = kTransmissionLobes;
  out.transmission = part.eval(wo, wi);
  return out;
}

}  // namespace tray

#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

#include "core/light_paths.h"
#include "core/material.h"
#include "core/sampling.h"
#include "materials/bsdf_layers.h"
#include "materials/dielectric.h"
#include "materials/diffuse_transmission.h"
#include "materials/ggx_mixture_lanes.h"
#include "materials/ggx_reflection.h"
#include "materials/hair_bsdf.h"
#include "materials/lambert.h"

namespace tray {

/// glTF metallic-roughness as a physically based BSDF, a weighted sum of lobes
/// (glTF 2.0 appendix B, KHR_materials_transmission):
///   metallic                  x GGX reflection, Schlick Fresnel with F0 = baseColor
///   (1-metallic) transmission x dielectric (GGX or smooth), exact Fresnel, tinted by baseColor
///   (1-metallic)(1-transm.)   x plastic: c GGX coat (exact Fresnel, ior) +
///                               (1 - c F(cos_o)) Lambert(baseColor)
/// alpha = roughness^2. The coat strength c fades from 1 to 0 as roughness goes 0.9 -> 1, so
/// roughness 1 with metallic 0 is exactly Lambert: what exporters write for matte surfaces
/// (Mitsuba's `diffuse`, the Cornell box) -- documented in docs/path-tracing.md.
/// KHR_materials_specular weights and tints the plastic's coat Fresnel (GgxReflectionLobe).
/// Layers go over all of it, each f = f_layer + baseScale f_below (materials/bsdf_layer.h),
/// outermost first as materials/bsdf_layers.h registers them: KHR_materials_clearcoat's GGX
/// dielectric coat with its own normal (clearcoat_layer.h), then KHR_materials_sheen's Charlie
/// sheen (sheen_layer.h).
/// KHR_materials_anisotropy stretches the GGX lobes (metal, coat, glass) along the material's
/// direction: the local frame's x axis is that direction, alpha_x = mix(alpha, 1, strength^2),
/// alpha_y = alpha. KHR_materials_diffuse_transmission replaces the Lambert lobe with
/// (1 - dt) Lambert(baseColor) + dt Lambert transmission(colour) on the far side
/// (materials/diffuse_transmission.h). Both take the per-lobe scalar code (scalarMix_), not
/// the one-text mixture the SIMD glossy stage shares (docs/materials-extensions.md).
/// Built per shading point on the stack; directions are world-space, the shading normal n
/// faces wo's side.
class Bsdf {
 public:
  /// eta = n_t / n_i across this interface for light arriving from n's side (from the
  /// MediumStack; for opaque materials simply ior / n_outside). The frame around n is built
  /// here, in place: taking a Frame the caller had just built cost a store-forwarding stall
  /// per vertex (see setSpawnRay in core/ray.h).
  Bsdf(const ShadingMaterial& m, const Vec3& n, float eta)
      : frame_(Frame::fromNormal(n)), diffuse_{m.baseColor}, coatEta_(eta) {
    // TRAY_materials_hair: the hair BSDF alone (materials/hair_bsdf.h), no glTF lobe or layer.
    if (m.hair) {
      initHair(*m.hair, m.tangent, n);
      return;
    }
    // A lone Lambert lobe under no layer (matte: metallic 0, roughness 1, no transmission)
    // with some albedo: nothing else is built. Building every lobe took 222 instructions per
    // vertex (callgrind, Cornell box). The weights are the general path's up to the sign of
    // zero, which only meets tests > 0 and sums with a positive term; coatTinted_ false:
    // coatFresnel is 0 either way with coat_ 0 (evalLobes reads it). NaN factors go the general
    // way, whose classification this test matches (coat_ > 0 iff roughness < 1; a NaN weight
    // makes wPlastic_ NaN and the lobe inert).
    if (isLambertOnly(m)) {
      wMetal_ = 0, wGlass_ = 0, wPlastic_ = 1, coat_ = 0;
      coatTinted_ = false;
      hasNonDelta_ = true;
      lambertOnly_ = true;
      probCached_ = false;
      scalarMix_ = false, diffuseTransmits_ = false, iridescent_ = false;
      only_ = Only::kDiffuse;
      return;
    }
    initLobes(m, eta);
  }
  /// The untextured material (tests).
  Bsdf(const Material& m, const Vec3& n, float eta) : Bsdf(ShadingMaterial::of(m, n), n, eta) {}
  Color eval(const Vec3& wo, const Vec3& wi) const;
  float pdf(const Vec3& wo, const Vec3& wi) const;
  /// eval and pdf together (next-event estimation needs both), with one change of frame.
  Color eval(const Vec3& wo, const Vec3& wi, float& pdf) const {
    return lambertOnly_ ? lambertEval(wo, wi, pdf) : layersEval(wo, wi, pdf);
  }
  /// uc picks the lobe (and reflection vs refraction), u the direction. wi comes back in world
  /// space; an invalid sample has pdf 0.
  BsdfSample sample(const Vec3& wo, float uc, Vec2 u) const {
    return lambertOnly_ ? lambertSample(wo, u) : layersSample(wo, uc, u);
  }
  /// The adjoint BSDF, for importance carried from the lights (photons, bidirectional light
  /// subpaths): f*(wo, wi) = f(wi, wo) (Veach 1997, 5.2; pbrt-v4's TransportMode::Importance).
  /// Only transmission differs: radiance is scaled by 1/eta^2 crossing a refractive boundary,
  /// importance is not. Every lobe that reaches wi's side below n is the dielectric's, whose
  /// eta relative to wo (n faces wo) is the constructor's. Shading normals' asymmetry (Veach
  /// 5.3) is the caller's: it knows the geometric normal.
  Color evalImportance(const Vec3& wo, const Vec3& wi, float& pdf) const {
    if (only_ == Only::kHair) return hairImportance(wo, wi, pdf);
    Color f = eval(wo, wi, pdf);
    if (wGlass_ > 0 && dot(wi, frame_.n) < 0) {
      if (!diffuseTransmits_) return f * (coatEta_ * coatEta_);
      // KHR_materials_diffuse_transmission's share below is not refracted: only the glass
      // lobe's part (the same Bsdf without diffuse transmission, whose Lambert lobe is 0 on
      // the far side) takes the factor.
      Bsdf glassOnly = *this;
      glassOnly.diffuseTransmits_ = false;
      float unused;
      f += glassOnly.eval(wo, wi, unused) * (coatEta_ * coatEta_ - 1.0f);
    }
    return f;
  }
  /// sample() for importance: a sampled transmission's f without the 1/eta^2 (etaScale).
  BsdfSample sampleImportance(const Vec3& wo, float uc, Vec2 u) const {
    BsdfSample s = sample(wo, uc, u);
    if (s.transmission && s.etaScale > 0) s.f = s.f * (1.0f / s.etaScale);
    if (only_ == Only::kHair && s.pdf > 0) {
      float unused;
      s.f = hairImportance(wo, s.wi, unused);
    }
    return s;
  }
  /// False when every lobe is a delta: light sampling cannot help and MIS is off.
  bool hasNonDelta() const { return hasNonDelta_ || layers_.anyNonDelta(); }
  /// True when light can also scatter to the far side of the surface.
  bool transmits() const { return wGlass_ > 0 || diffuseTransmits_ || only_ == Only::kHair; }
  /// Nothing but a Lambert lobe of albedo m.baseColor (matte): the SIMD matte stage repeats
  /// eval and sample for it (integrators/matte_batch.h). The constructor's test: metallic 0,
  /// roughness 1, no transmission, no layer (clearcoat, sheen), some albedo.
  static bool isLambertOnly(const ShadingMaterial& m) {
    const Color& a = m.baseColor;
    return !m.hair && m.metallic <= 0 && m.transmission <= 0 && !(m.roughness < 1.0f) &&
           !(m.diffuseTransmission > 0) && (a.x > 0 || a.y > 0 || a.z > 0) &&
           !BsdfLayers::anyApplies(m);
  }
  /// Metal and plastic (GGX reflection, its dielectric coat and Lambert) and nothing else: no
  /// transmission, layer (clearcoat, sheen) or KHR_materials_specular tint, some lobe in use, not a
  /// lone Lambert lobe, and some lobe that is not a delta (mirrors only beside a Lambert lobe). The
  /// SIMD glossy stage repeats eval and sample for it (integrators/glossy_batch.h): initLobes'
  /// Only::kMetal or kMixture, whose lone metal lobe is the mixture with weight 1.
  /// Out of line: inlined, it cost the matte vertices' step more than the call costs these.
  static bool isGgxMixture(const ShadingMaterial& m);
  /// Smooth glass alone (initLobes' Only::kGlass below the smooth limit): metallic 0,
  /// transmission 1, roughness small enough for two delta lobes, no layer. Every
  /// lobe is a delta (no light sample); the SIMD delta stage repeats sample for it
  /// (integrators/delta_batch.h). Out of line, as isGgxMixture.
  static bool isSmoothGlass(const ShadingMaterial& m);
  bool lambertOnly() const { return lambertOnly_; }
  const Frame& frame() const { return frame_; }

  /// eval split by lobe kind (core/light_paths.h): the three parts sum to eval(wo, wi) up to
  /// float rounding. For light-path AOVs, at a path's first scattering only.
  LobeSplit evalLobes(const Vec3& wo, const Vec3& wi) const;

  /// The same, in the local frame (tests use these directly), without the layers.
  Color evalLocal(const Vec3& wo, const Vec3& wi) const;
  float pdfLocal(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sampleLocal(const Vec3& wo, float uc, Vec2 u) const;

 private:
  /// Each lobe's probability at wo, and coatFresnel(wo), which the Lambert lobe's weight also
  /// reads (materials/ggx_mixture_lanes.h).
  using Probabilities = MixtureProbabilitiesOf<float>;
  /// The one lobe with any weight, when there is only one (matte, pure metal, pure glass):
  /// sample, eval and pdf then skip the mixture's bookkeeping. Same values, fewer
  /// instructions (7% of the Cornell box render's, callgrind on bench/path_bench).
  /// kHair: TRAY_materials_hair's fibre BSDF alone (hair_), outside the glTF mixture.
  enum class Only : uint8_t { kMixture, kMetal, kGlass, kDiffuse, kNothing, kHair };
  /// Storage for a member that only some materials read: left unbuilt (no stores) until one
  /// assigns it. The lone Lambert lobe (every matte surface, all of the Cornell box) builds
  /// none of them; reads are guarded by the weights and flags that say the member is in use.
  template <class T>
  union Slot {
    T value;
    Slot() {}  // NOLINT: deliberately unbuilt
    T* operator->() { return &value; }
    const T* operator->() const { return &value; }
  };
  // Everything but the lone Lambert lobe, and the layers.
  void initLobes(const ShadingMaterial& m, float eta);
  /// The frame whose x axis is KHR_materials_anisotropy's direction (projected onto the
  /// tangent plane; the default frame's when it has no length there).
  static Frame anisotropicFrame(const Vec3& n, const Vec3& direction);
  /// The Lambert (or diffuse-transmission) lobe's value and pdf, with the lobe-kind mask.
  Color diffuseEval(const Vec3& wo, const Vec3& wi) const;
  float diffusePdf(const Vec3& wo, const Vec3& wi) const {
    return diffuseTransmits_ ? dtLobe_->pdf(wo, wi) : diffuse_.pdf(wo, wi);
  }
  void initHair(const HairParams& p, const Vec3& tangent, const Vec3& n);
  /// The hair model is not reciprocal (its offset h is read from wo: materials/hair_bsdf.h), so
  /// its adjoint is stated: f*(wo, wi) = f(wi, wo) (Veach 1997, 3.7.6), with the pdf of
  /// sampling wi from wo.
  Color hairImportance(const Vec3& wo, const Vec3& wi, float& pdf) const {
    float unused;
    hair_->eval(wo, wi, pdf);
    return hair_->eval(wi, wo, unused);
  }
  Color layersEval(const Vec3& wo, const Vec3& wi, float& pdf) const;
  BsdfSample layersSample(const Vec3& wo, float uc, Vec2 u) const;
  /// The lone Lambert lobe in world space: only the cosines to n (and the frame to place the
  /// sampled direction).
  Color lambertEval(const Vec3& wo, const Vec3& wi, float& pdf) const {
    return lambertEvalPdf(diffuse_.albedo, dot(wo, frame_.n), dot(wi, frame_.n), pdf);
  }
  BsdfSample lambertSample(const Vec3& wo, Vec2 u) const {
    // LambertLobe::sample on wo's side (its local z: Lambert reads nothing else), then to world
    // space, without sampleLocal's mixture bookkeeping. No pdf check: z >= 2^-11 (even for a
    // NaN disk point, std::max keeps the floor), so the pdf is positive and finite.
    BsdfSample s = diffuse_.sample(Vec3(0.0f, 0.0f, dot(wo, frame_.n)), u);
    s.wi = frame_.toWorld(s.wi);
    return s;
  }
  /// Depends on wo.z alone. NEE's eval and the sample at one vertex ask at the same wo: the
  /// last answer is kept (see probWoZ_).
  const Probabilities& probabilities(const Vec3& wo) const {
    if (!probCached_ || std::bit_cast<uint32_t>(wo.z) != probWoZ_) {
      prob_.value = computeProbabilities(wo);
      probWoZ_ = std::bit_cast<uint32_t>(wo.z);
      probCached_ = true;
    }
    return prob_.value;
  }
  Probabilities computeProbabilities(const Vec3& wo) const;
  /// evalLocal and pdfLocal of a mixture in one pass, given p = probabilities(wo); ggxPdf gets
  /// the metal and coat lobes' own pdf (0 when neither lobe is in use). A float rather than
  /// the whole GgxReflectionLobe::Terms: copying that out cost a store-forwarding stall.
  Color mixtureEvalPdf(const Vec3& wo, const Vec3& wi, const Probabilities& p, float& pdf,
                       float& ggxPdf) const;
  /// The mixture as the one-text functions read it (materials/ggx_mixture_lanes.h), with the
  /// lobe kinds eval includes.
  GgxMixtureOf<Vec3> mixture() const;
  /// The coat's Fresnel colour at a microfacet cosine (exact, or KHR_materials_specular's tint).
  auto coatFresnelAt() const {
    return [this](float cosOM) { return coatLobe_->fresnel(cosOM); };
  }
  /// The metal's Fresnel colour at a microfacet cosine, for an iridescent metal (the lobe's).
  auto metalFresnelAt() const {
    return [this](const Vec3&, float cosOM) { return metal_->fresnel(cosOM); };
  }
  /// The glass lobe's value (where eval includes it) and pdf (where it can be sampled), for the
  /// mixture's sums: the glass lobe stays scalar.
  auto glassAt(const Probabilities& p) const {
    return [this, &p](const Vec3& wo, const Vec3& wi, float& glassPdf) {
      glassPdf = p.glass > 0 ? glass_->pdf(wo, wi) : 0.0f;
      return wGlass_ > 0 && includesGlass(wo, wi) ? glass_->eval(wo, wi) : Color(0.0f);
    };
  }
  float coatFresnel(const Vec3& wo) const;
  // The base material (everything below the layers), in world space.
  Color baseEval(const Vec3& wo, const Vec3& wi, float& pdf) const;
  BsdfSample baseSample(const Vec3& wo, float uc, Vec2 u) const;
  // The layers over the base (materials/bsdf_layers.h), from layer I down: I = 0 is all of it,
  // I = BsdfLayers::kCount the base alone.
  template <size_t I>
  Color evalFrom(const Vec3& wo, const Vec3& wi, float& pdf) const;
  template <size_t I>
  BsdfSample sampleFrom(const Vec3& wo, float uc, Vec2 u) const;
  Frame frame_;
  float wMetal_, wGlass_, wPlastic_, coat_;
  // Built by initLobes: read only where their weights (wMetal_, wGlass_, wPlastic_ x coat_)
  // are positive, which the lone Lambert lobe's are not.
  Slot<GgxReflectionLobe> metal_, coatLobe_;
  Slot<DielectricLobe> glass_;
  Slot<HairBsdf> hair_;  ///< only_ == Only::kHair
  /// The Lambert lobe; with diffuse transmission its albedo is reflect + transmit (for the
  /// lobe's probability) and dtLobe_ gives its value.
  LambertLobe diffuse_;
  Slot<DiffuseTransmissionLobe> dtLobe_;
  /// The per-lobe scalar code rather than the one-text mixture (anisotropy, diffuse
  /// transmission: the mixture has one isotropic alpha and Lambert reflection only).
  bool scalarMix_;
  bool diffuseTransmits_;  ///< dtLobe_ is built and replaces diffuse_'s value
  float coatEta_;
  bool coatTinted_;    ///< KHR_materials_specular or _iridescence changed the coat's Fresnel
  bool iridescent_;    ///< KHR_materials_iridescence: metal and coat carry a thin film
  BsdfLayers layers_;  ///< clearcoat, sheen, ...: those the material has
  bool hasNonDelta_;
  // probabilities()' last answer and the bits of its wo.z: one computation per vertex instead
  // of two (callgrind spheres 96x96 16spp: trace 613.2M -> 606.7M).
  mutable bool probCached_;
  mutable uint32_t probWoZ_;
  mutable Slot<Probabilities> prob_;
  /// Nothing but a Lambert lobe (no clearcoat, no sheen): eval and sample take the short path.
  /// Set only by the constructor's early exit; the other members it leaves unbuilt.
  bool lambertOnly_;
  Only only_;
  /// Lobe kinds eval includes (evalLobes evaluates a copy with one kind at a time).
  uint8_t lobeMask_ = kAllLobes;
  bool includes(LobeKinds k) const { return lobeMask_ & k; }
  /// A dielectric's value from wo to wi counts as specular (reflection) or transmission.
  bool includesGlass(const Vec3& wo, const Vec3& wi) const {
    return includes(sameHemisphere(wo, wi) ? kSpecularLobes : kTransmissionLobes);
  }
};

}  // namespace tray

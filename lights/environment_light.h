#pragma once
#include "core/light.h"
#include "core/light_bounds.h"
#include "core/sampling.h"

namespace tray {

/// TRAY_environment's background as a light: a constant radiance from every direction
/// (pbrt-v4 12.5.2's UniformInfiniteLight; an image-based one would replace Le and the
/// sampling). Samples follow a cosine lobe about the receiver's shading normal: for a diffuse
/// surface the light and BSDF pdfs are then equal and MIS splits the integral exactly (a white
/// furnace is noise-free). A receiver that also transmits mixes in the uniform sphere, so
/// directions below its normal keep a positive pdf.
class EnvironmentLight final : public Light {
 public:
  EnvironmentLight(const Color& Le, float sceneRadius) : Le_(Le), sceneRadius_(sceneRadius) {}
  static constexpr float kCosineShareTwoSided = 0.5f;

  uint8_t flags() const override { return kLightInfinite; }
  float power() const override {
    return luminance(Le_) * 4.0f * kPi * kPi * sceneRadius_ * sceneRadius_;
  }
  LightBounds bounds() const override { return LightBounds::ambient(luminance(Le_)); }
  Color Le(const Vec3&) const override { return Le_; }
  LightSample sample(const LightSampleContext& ctx, Vec2 u) const override {
    LightSample s;
    const float share = ctx.transmits ? kCosineShareTwoSided : 1.0f;
    if (u.x < share) {
      // A share of 1 leaves u.x as it was (u.x / 1 = u.x < 1): no division.
      if (ctx.transmits) u.x = std::min(u.x / share, 0.99999994f);
      s.wi = sampleCosineAbout(ctx.n, u);
    } else {
      u.x = (u.x - share) / (1.0f - share);
      s.wi = normalize(sampleUniformSphere(u));
    }
    s.L = Le_;
    s.pdf = pdf(ctx, s.wi, Vec3(), Vec3());
    s.infinite = true;
    return s;
  }
  /// Uniform directions; origins uniform on the world's disk facing each direction.
  LightLeSample sampleLe(Vec2 u1, Vec2 u2, const WorldSphere& world) const override;
  LightLePdf pdfLe(const Vec3& p, const Vec3& n, const Vec3& w,
                   const WorldSphere& world) const override;
  float pdf(const LightSampleContext& ctx, const Vec3& wi, const Vec3&,
            const Vec3&) const override {
    if (!ctx.transmits) return cosineHemispherePdf(dot(ctx.n, wi));
    return kCosineShareTwoSided * cosineHemispherePdf(dot(ctx.n, wi)) +
           (1.0f - kCosineShareTwoSided) * kUniformSpherePdf;
  }

 private:
  Color Le_;
  float sceneRadius_ = 1;
};

}  // namespace tray

#pragma once
#include "core/sampling.h"
#include "lights/light_sample.h"

namespace tray {

/// TRAY_environment's background: a constant radiance from every direction. Samples follow a
/// cosine lobe about the receiver's shading normal: for a diffuse surface the light and BSDF
/// pdfs are then equal and MIS splits the integral exactly (a white furnace is noise-free).
/// A receiver that also transmits (`bothSides`) mixes in the uniform sphere, so directions
/// below its normal keep a positive pdf.
struct EnvironmentLight {
  Color Le;
  float sceneRadius = 1;
  static constexpr float kCosineShareTwoSided = 0.5f;
  float power() const { return luminance(Le) * 4.0f * kPi * kPi * sceneRadius * sceneRadius; }
  LightSample sample(const Vec3& n, bool bothSides, Vec2 u) const {
    LightSample s;
    const float share = bothSides ? kCosineShareTwoSided : 1.0f;
    if (u.x < share) {
      u.x = std::min(u.x / share, 0.99999994f);
      s.wi = Frame::fromNormal(n).toWorld(sampleCosineHemisphere(u));
    } else {
      u.x = (u.x - share) / (1.0f - share);
      s.wi = sampleUniformSphere(u);
    }
    s.wi = normalize(s.wi);
    s.L = Le;
    s.pdf = pdf(n, bothSides, s.wi);
    s.infinite = true;
    return s;
  }
  float pdf(const Vec3& n, bool bothSides, const Vec3& wi) const {
    if (!bothSides) return cosineHemispherePdf(dot(n, wi));
    return kCosineShareTwoSided * cosineHemispherePdf(dot(n, wi)) +
           (1.0f - kCosineShareTwoSided) * kUniformSpherePdf;
  }
};

}  // namespace tray

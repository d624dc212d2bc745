#pragma once
#include "core/light.h"
#include "core/light_bounds.h"
#include "core/light_desc.h"
// samplePunctualLight, written once for scalar code and the SIMD stages.
#include "lights/punctual_light_lanes.h"

namespace tray {

/// KHR_lights_punctual point, spot and directional lights: delta lights, reached only by light
/// sampling (pbrt-v4 12.2, 12.4). Units as the shared reference notes state: point/spot
/// radiant intensity color x intensity, directional irradiance color x intensity.
class PunctualLight final : public Light {
 public:
  PunctualLight(const PunctualLightDesc& desc, float sceneRadius)
      : desc_(desc), sceneRadius_(sceneRadius) {
    lanes_.directional = desc.type == PunctualLightDesc::Type::kDirectional;
    lanes_.spot = desc.type == PunctualLightDesc::Type::kSpot;
    lanes_.position = desc.position, lanes_.direction = desc.direction;
    lanes_.intensity = desc.intensity;
    lanes_.cosOuter = std::cos(desc.outerConeAngle);
    lanes_.cosInner = std::cos(desc.innerConeAngle);
  }

  uint8_t flags() const override {
    return desc_.type == PunctualLightDesc::Type::kDirectional ? kLightDeltaDirection
                                                                : kLightDeltaPosition;
  }
  float power() const override {
    float I = luminance(desc_.intensity);
    switch (desc_.type) {
      case PunctualLightDesc::Type::kPoint:
        return 4.0f * kPi * I;
      case PunctualLightDesc::Type::kSpot:  // pbrt-v4's estimate of the smooth cone's solid angle
        return 2.0f * kPi * I *
               (1.0f - 0.5f * (std::cos(desc_.innerConeAngle) + std::cos(desc_.outerConeAngle)));
      case PunctualLightDesc::Type::kDirectional:  // through the scene's bounding disk
        return kPi * sceneRadius_ * sceneRadius_ * I;
    }
    return 0.0f;
  }
  /// Point: all directions, phi = intensity; spot: the outer cone, where it emits at most its
  /// intensity (theta_e 0: nothing outside); directional: its irradiance.
  LightBounds bounds() const override {
    const float I = luminance(desc_.intensity);
    if (desc_.type == PunctualLightDesc::Type::kDirectional)
      return LightBounds::directional(-desc_.direction, I);
    Bounds3 box;
    box.extend(desc_.position);
    if (desc_.type == PunctualLightDesc::Type::kPoint)
      return LightBounds::finite(box, Vec3(0, 0, 1), I, -1.0f, 0.0f, false);
    return LightBounds::finite(box, desc_.direction, I, std::cos(desc_.outerConeAngle), 1.0f,
                               false);
  }
  LightSample sample(const LightSampleContext& ctx, Vec2) const override {
    const PunctualLightSampleOf<Vec3> l = samplePunctualLight(lanes_, ctx.p);
    LightSample s;
    s.delta = true;
    s.infinite = lanes_.directional;
    if (!l.valid) return s;
    s.wi = l.wi, s.L = l.L;
    s.p = desc_.position;
    s.pdf = 1;
    return s;
  }
  /// Point: uniform over the sphere; spot: uniform in the outer cone; directional: parallel
  /// rays from a disk of the world's radius facing the scene.
  LightLeSample sampleLe(Vec2 u1, Vec2 u2, const WorldSphere& world) const override;
  LightLePdf pdfLe(const Vec3& p, const Vec3& n, const Vec3& w,
                   const WorldSphere& world) const override;
  /// The light as samplePunctualLight (and the SIMD stages' punctual table) reads it.
  const PunctualLightOf<Vec3>& lanes() const { return lanes_; }
  float pdf(const LightSampleContext&, const Vec3&, const Vec3&, const Vec3&) const override {
    return 0.0f;  // a direction sampled otherwise never meets a delta light
  }

 private:
  PunctualLightDesc desc_;
  float sceneRadius_ = 1;  ///< for a directional light's power
  PunctualLightOf<Vec3> lanes_;
};

}  // namespace tray

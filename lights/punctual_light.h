#pragma once
#include "core/light.h"
#include "lights/light_sample.h"

namespace tray {

/// KHR_lights_punctual point, spot and directional lights: delta lights, reached only by light
/// sampling. Units as the shared reference notes state: point/spot radiant intensity
/// color x intensity, directional irradiance color x intensity.
struct PunctualLight {
  Light light;
  float sceneRadius = 1;  ///< for a directional light's power

  float power() const {
    float I = luminance(light.intensity);
    switch (light.type) {
      case Light::Type::kPoint:
        return 4.0f * kPi * I;
      case Light::Type::kSpot:  // pbrt-v4's estimate of the smooth cone's solid angle
        return 2.0f * kPi * I *
               (1.0f - 0.5f * (std::cos(light.innerConeAngle) + std::cos(light.outerConeAngle)));
      case Light::Type::kDirectional:
        return kPi * sceneRadius * sceneRadius * I;
    }
    return 0.0f;
  }
  LightSample sample(const Vec3& ref) const {
    LightSample s;
    s.delta = true;
    if (light.type == Light::Type::kDirectional) {
      s.wi = -light.direction;
      s.L = light.intensity;
      s.infinite = true;
      s.pdf = 1;
      return s;
    }
    Vec3 d = light.position - ref;
    float dist2 = lengthSquared(d);
    if (!(dist2 > 0)) return s;
    s.wi = d / std::sqrt(dist2);
    s.p = light.position;
    s.L = light.intensity * (light.spotFalloff(-s.wi) / dist2);
    if (isBlack(s.L)) return s;
    s.pdf = 1;
    return s;
  }
};

}  // namespace tray

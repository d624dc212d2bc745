#pragma once
// Lights as a scene describes them (plain data, filled by io/ or by tests). The renderer's
// light objects (core/light.h, lights/) are built from these by LightSet.
#include "core/math.h"

namespace tray {

/// KHR_lights_punctual light in world space. Radiometric meaning (see shared reference notes):
/// point/spot: radiant intensity = color * intensity (irradiance I/d^2); directional:
/// irradiance = color * intensity. glTF's `range` is ignored.
struct PunctualLightDesc {
  enum class Type { kPoint, kSpot, kDirectional };
  Type type = Type::kPoint;
  Color intensity{1.0f};   ///< color x intensity
  Vec3 position;           ///< point, spot
  Vec3 direction{0, 0, -1};  ///< unit direction the light travels (spot, directional)
  float innerConeAngle = 0.0f;
  float outerConeAngle = kPi / 4.0f;
  /// Spot attenuation at the unit direction from the light to a point (glTF's smooth falloff).
  float spotFalloff(const Vec3& lightToPoint) const;
};

/// TRAY_environment: constant ambient term (Whitted) and background radiance (the
/// environment light, lights/environment_light.h).
struct Environment {
  Color ambient{0.0f};
  Color background{0.0f};
  bool transparent = false;  ///< camera rays that escape give RGBA 0 (as --transparent)
};

}  // namespace tray

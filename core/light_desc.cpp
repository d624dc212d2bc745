#include "core/light_desc.h"

namespace tray {

float PunctualLightDesc::spotFalloff(const Vec3& lightToPoint) const {
  if (type != Type::kSpot) return 1.0f;
  // KHR_lights_punctual's reference implementation: linear in cos between the cone angles,
  // squared for a smooth edge.
  float cosOuter = std::cos(outerConeAngle), cosInner = std::cos(innerConeAngle);
  float cd = dot(lightToPoint, direction);
  float t = std::clamp((cd - cosOuter) / std::max(cosInner - cosOuter, 1e-4f), 0.0f, 1.0f);
  return t * t;
}

}  // namespace tray

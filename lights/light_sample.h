#pragma once
#include "core/math.h"

namespace tray {

/// A direction towards a light from a reference point, with what arrives along it.
struct LightSample {
  Color L;                ///< radiance arriving (delta lights: intensity / d^2 or irradiance)
  Vec3 wi;                ///< unit direction from the reference point towards the light
  Vec3 p;                 ///< the point on the light (finite lights) for the shadow ray
  float pdf = 0;          ///< solid-angle density of wi (1 for delta lights); 0 = no sample
  bool delta = false;     ///< point, spot, directional: MIS does not apply
  bool infinite = false;  ///< directional, environment: the shadow ray is unbounded
  bool valid() const { return pdf > 0; }
};

}  // namespace tray

#pragma once
// The irradiance an environment map gives a surface of each normal, unshadowed, from the
// map's first nine spherical-harmonic coefficients (Ramamoorthi & Hanrahan 2001, "An
// Efficient Representation for Irradiance Environment Maps"): the clamped cosine is so smooth
// that bands 0..2 hold all but about 1% of it for any lighting (their section 3). Whitted's
// integrator lights diffuse surfaces with it (it samples no area of any light).
#include <array>

#include "core/light.h"

namespace tray {

class EnvironmentIrradiance {
 public:
  /// Projects light.Le over the sphere onto bands 0..2 by a midpoint rule on a latitude-longitude
  /// grid of `width` x width/2 cells (fine enough for a map of that size; irradiance keeps
  /// only low frequencies).
  explicit EnvironmentIrradiance(const Light& light, int width = 256);
  /// E(n) = integral of Le(w) max(0, n.w) dw for unit n (Ramamoorthi & Hanrahan, eq. 7-8).
  Color irradiance(const Vec3& n) const;

 private:
  std::array<Color, 9> coefficients_{};  ///< L_lm x A_l (the cosine lobe's band factors)
};

}  // namespace tray

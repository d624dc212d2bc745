#pragma once
// Beer–Lambert absorption inside KHR_materials_volume media, shared by the estimators that
// cross them (path, bdpt).
#include <cmath>

#include "materials/medium_stack.h"

namespace tray {

/// Beer-Lambert transmittance exp(-sigma_a d) per channel (KHR_materials_volume).
inline Color transmittance(const Color& sigmaA, float d) {
  return {std::exp(-sigmaA.x * d), std::exp(-sigmaA.y * d), std::exp(-sigmaA.z * d)};
}

/// Absorption of the medium beyond a refractive surface: the one in effect once crossed.
inline Color farSideAbsorption(const MediumStack& media, int id, const Material& m, bool entering) {
  MediumStack far = media;
  far.cross(id, m, entering);
  return far.currentAbsorption();
}

/// Extinction of the medium beyond a refractive surface (sigma_a + sigma_s where it scatters,
/// docs/subsurface.md): what a shadow ray crossing it is attenuated by.
inline Color farSideExtinction(const MediumStack& media, int id, const Material& m, bool entering) {
  MediumStack far = media;
  far.cross(id, m, entering);
  return far.currentExtinction();
}

}  // namespace tray

#pragma once
// Choices every front end makes the same way: which camera and what image size.
#include <string>

#include "core/scene.h"

namespace tray {

/// Camera `index` of the scene (throws tray::Error if out of range); -1: the first camera, or
/// one framing the scene's bounds when it has none.
CameraDesc chooseCamera(const Scene& scene, int index);

struct ImageSize {
  int width = 640, height = 480;
};

/// What a scene's emissive surfaces give off, to decide whether it is lit.
struct EmissionSummary {
  /// Irradiance of the default key light.
  static constexpr float kDefaultIrradiance = 2.5f;
  /// Emitters count as lighting when their power is at least this share of what the default
  /// key light would pour onto the scene (its irradiance over a quarter of the surface area,
  /// a convex body's mean projected area).
  static constexpr double kMeaningfulShare = 0.01;
  double meshPower = 0;    ///< sum over emissive triangles of area x pi L (L: factor x mean texel)
  double surfaceArea = 0;  ///< world area of every mesh triangle
  bool emissiveShapes = false;
  bool meaningful() const;
};
EmissionSummary summarizeEmission(const Scene& scene);

/// A scene with no light of meaningful power (no punctual light, a black TRAY_environment,
/// and emitters too weak to light it: e.g. a mostly black emissive texture) would render black,
/// which is never what a user wants from a glTF asset made for viewers that bring their own
/// light. Adds TRay's default lighting, as a viewer's headlight: a directional key light of
/// irradiance 2.5 arriving from above-left behind the camera, and a uniform environment of
/// 0.1 (ambient and background). Returns whether it did.
bool addDefaultLightingIfUnlit(Scene& scene, const CameraDesc& camera);

/// Parses "WxH"; empty: 640 wide with the height from the camera's aspect ratio (4:3 if unset).
ImageSize resolveImageSize(const std::string& text, const CameraDesc& camera);

}  // namespace tray

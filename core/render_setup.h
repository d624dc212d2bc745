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

/// A scene with no light at all (no punctual light, no emissive material, a black
/// TRAY_environment) would render black, which is never what a user wants from a glTF asset
/// made for viewers that bring their own light. Adds TRay's default lighting, as a viewer's
/// headlight: a directional key light of irradiance 2.5 arriving from above-left behind the
/// camera, and a uniform environment of 0.1 (ambient and background). Returns whether it did.
bool addDefaultLightingIfUnlit(Scene& scene, const CameraDesc& camera);

/// Parses "WxH"; empty: 640 wide with the height from the camera's aspect ratio (4:3 if unset).
ImageSize resolveImageSize(const std::string& text, const CameraDesc& camera);

}  // namespace tray

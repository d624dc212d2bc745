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

/// Parses "WxH"; empty: 640 wide with the height from the camera's aspect ratio (4:3 if unset).
ImageSize resolveImageSize(const std::string& text, const CameraDesc& camera);

}  // namespace tray

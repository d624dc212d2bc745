#include "core/render_setup.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace tray {

CameraDesc chooseCamera(const Scene& scene, int index) {
  if (index >= 0) {
    if (size_t(index) >= scene.cameras.size())
      throw Error(scene.sourcePath + ": --camera " + std::to_string(index) + " but the scene has " +
                  std::to_string(scene.cameras.size()) + " camera(s)");
    return scene.cameras[size_t(index)];
  }
  if (!scene.cameras.empty()) return scene.cameras.front();
  return Camera::framing(scene.bounds(), 4.0f / 3.0f);
}

ImageSize resolveImageSize(const std::string& text, const CameraDesc& camera) {
  ImageSize s;
  if (text.empty()) {
    float aspect = camera.aspectRatio > 0 ? camera.aspectRatio : 4.0f / 3.0f;
    s.height = std::max(1, int(std::lround(s.width / aspect)));
    return s;
  }
  int consumed = 0;
  if (std::sscanf(text.c_str(), "%dx%d%n", &s.width, &s.height, &consumed) != 2 ||
      consumed != int(text.size()) || s.width <= 0 || s.height <= 0 || s.width > 16384 ||
      s.height > 16384)
    throw Error("--resolution '" + text + "': expected WxH with 1..16384 pixels per side");
  return s;
}

}  // namespace tray

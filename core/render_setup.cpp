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

bool addDefaultLightingIfUnlit(Scene& scene, const CameraDesc& camera) {
  if (!scene.lights.empty() || !isBlack(scene.environment.ambient) ||
      !isBlack(scene.environment.background))
    return false;
  for (const Material& m : scene.materials)
    if (!isBlack(m.emissive)) return false;
  // glTF cameras look down -Z with +Y up; the key light travels forward, down and right.
  const Vec3 forward = normalize(camera.toWorld.vector(Vec3(0, 0, -1)));
  const Vec3 up = normalize(camera.toWorld.vector(Vec3(0, 1, 0)));
  const Vec3 right = normalize(cross(forward, up));
  PunctualLightDesc key;
  key.type = PunctualLightDesc::Type::kDirectional;
  key.intensity = Color(2.5f);
  key.direction = normalize(forward - 0.6f * up + 0.4f * right);
  scene.lights.push_back(key);
  scene.environment.ambient = Color(0.1f);
  scene.environment.background = Color(0.1f);
  return true;
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

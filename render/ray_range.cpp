#include "render/ray_range.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace tray {
namespace {

bool inRange(float v) {
  return std::isfinite(v) && std::fabs(v) <= kMaxRayCoordinate;
}
bool inRange(const Vec3& v) {
  return inRange(v.x) && inRange(v.y) && inRange(v.z);
}

std::string shown(const Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return text;
}

[[noreturn]] void refuse(const std::string& sceneName, const std::string& what) {
  throw Error(sceneName + ": " + what + ": beyond 1e17 (or not finite), rays from there are out " +
              "of the tracer's range");
}

}  // namespace

void checkRayRange(const std::string& sceneName, const Scene& scene, const CameraDesc& camera) {
  const std::string cam = "the camera '" + camera.name + "'";
  const Vec3 eye = camera.toWorld.point(Vec3(0.0f));
  if (!inRange(eye)) refuse(sceneName, cam + " is at " + shown(eye));
  for (const Mat4& step : camera.motion) {
    const Vec3 at = Transform(step).point(Vec3(0.0f));
    if (!inRange(at)) refuse(sceneName, cam + " moves to " + shown(at));
  }
  const struct {
    const char* name;
    float value;
  } lengths[] = {{"lens radius", camera.lensRadius},
                 {"focus distance", camera.focusDistance},
                 {"orthographic xmag", camera.xmag},
                 {"orthographic ymag", camera.ymag},
                 {"znear", camera.znear}};
  for (const auto& l : lengths)
    if (!inRange(l.value))
      refuse(sceneName, cam + "'s " + l.name + " is " + std::to_string(l.value));
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const PunctualLightDesc& l = scene.lights[i];
    if (l.type != PunctualLightDesc::Type::kDirectional && !inRange(l.position))
      refuse(sceneName, "punctual light " + std::to_string(i) + " is at " + shown(l.position));
  }
}

}  // namespace tray

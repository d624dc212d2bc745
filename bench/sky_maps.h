#pragma once
// Environment maps made in code, for tests and benches (no downloads, no image files in git):
// a sky gradient with a small, very bright sun disk; a dark room with a few bright windows;
// and a map of constant radiance per hemisphere (the furnace's closed form). Directions follow
// lights/image_environment_light.h's convention, unrotated.
#include <cmath>
#include <memory>

#include "core/light_desc.h"

namespace tray::maps {

/// The map direction at the centre of pixel (x, y).
inline Vec3 pixelDirection(int x, int y, int w, int h) {
  const float phi = 2.0f * kPi * (float(x) + 0.5f) / float(w);
  const float theta = kPi * (float(y) + 0.5f) / float(h);
  return {std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta)};
}

template <class F>
std::shared_ptr<EnvironmentMap> makeMap(int w, int h, const char* name, F radiance) {
  auto m = std::make_shared<EnvironmentMap>();
  m->name = name, m->width = w, m->height = h;
  m->rgb.resize(size_t(w) * size_t(h) * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Color c = radiance(pixelDirection(x, y, w, h));
      float* p = &m->rgb[(size_t(y) * size_t(w) + size_t(x)) * 3];
      p[0] = c.x, p[1] = c.y, p[2] = c.z;
    }
  return m;
}

/// A blue sky brightening towards the horizon, a grey-brown ground, and a sun disk of
/// `sunDegrees` angular radius and radiance `sun` towards `sunDir` (unit). With the defaults
/// the sun gives about 90% of the irradiance on an upward-facing surface.
inline std::shared_ptr<EnvironmentMap> sunSky(int w, int h, Vec3 sunDir = {0.4f, 0.6f, 0.69f},
                                              float sunDegrees = 2.0f, float sun = 20000.0f) {
  sunDir = normalize(sunDir);
  const float cosSun = std::cos(sunDegrees * kPi / 180.0f);
  return makeMap(w, h, "sun-sky", [&](const Vec3& d) {
    if (dot(d, sunDir) >= cosSun) return Color(sun, 0.92f * sun, 0.8f * sun);
    if (d.y < 0) return Color(0.25f, 0.2f, 0.15f);
    const float t = std::pow(1.0f - d.y, 3.0f);  // 0 at the zenith, 1 at the horizon
    return (1 - t) * Color(0.15f, 0.3f, 0.8f) + t * Color(0.8f, 0.85f, 0.95f);
  });
}

/// A dim room (radiance 0.05) with three bright windows (radiance 40) around the horizon.
inline std::shared_ptr<EnvironmentMap> windows(int w, int h) {
  return makeMap(w, h, "windows", [](const Vec3& d) {
    const float phi = std::atan2(d.x, -d.z);  // the map's u angle, -pi..pi
    for (float centre : {-2.0f, 0.3f, 2.2f})
      if (std::fabs(phi - centre) < 0.25f && d.y > 0.05f && d.y < 0.6f) return Color(40.0f);
    return Color(0.05f);
  });
}

/// Radiance `upper` for directions with y > 0 and `lower` below (h even: the equator is a
/// pixel edge).
inline std::shared_ptr<EnvironmentMap> hemispheres(int w, int h, Color upper, Color lower) {
  return makeMap(w, h, "hemispheres",
                 [&](const Vec3& d) { return d.y > 0 ? upper : lower; });
}

}  // namespace tray::maps

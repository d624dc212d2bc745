#pragma once
// Lights as a scene describes them (plain data, filled by io/ or by tests). The renderer's
// light objects (core/light.h, lights/) are built from these by LightSet.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/math.h"

namespace tray {

/// KHR_lights_punctual light in world space. Radiometric meaning (see shared reference notes):
/// point/spot: radiant intensity = color * intensity (irradiance I/d^2); directional:
/// irradiance = color * intensity. glTF's `range` is ignored.
struct PunctualLightDesc {
  enum class Type { kPoint, kSpot, kDirectional };
  Type type = Type::kPoint;
  Color intensity{1.0f};   ///< color x intensity
  Vec3 position;           ///< point, spot
  Vec3 direction{0, 0, -1};  ///< unit direction the light travels (spot, directional)
  float innerConeAngle = 0.0f;
  float outerConeAngle = kPi / 4.0f;
};

/// An equirectangular (latitude-longitude) radiance map in TRay's working space (linear
/// Rec.709), loaded by io/environment_map.h or made by tests. Row 0 is the top (+Y, v = 0);
/// the direction convention is Mitsuba 3's envmap (lights/image_environment_light.h).
/// An allocator whose value-initialisation leaves its elements unset: a vector's resize()
/// then reserves pages without touching them, so that memory becomes resident only as it is
/// written (a map decoded row by row; a file that lies about its size fails after the rows it
/// holds, not after a zero-fill of what it claims: issue 40).
template <class T>
struct UnsetOnResize : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UnsetOnResize<U>;
  };
  UnsetOnResize() = default;
  template <class U>
  UnsetOnResize(const UnsetOnResize<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

struct EnvironmentMap {
  std::string name;  ///< for messages: the file's path
  int width = 0, height = 0;
  /// width * height * 3, finite and >= 0 (resize() leaves new values unset: write them all).
  std::vector<float, UnsetOnResize<float>> rgb;
};

/// TRAY_environment: constant ambient term (Whitted) and background radiance (the
/// environment light, lights/environment_light.h); or, when `map` is set, an image-based
/// environment (lights/image_environment_light.h) that replaces `background`.
struct Environment {
  Color ambient{0.0f};
  Color background{0.0f};
  bool transparent = false;  ///< camera rays that escape give RGBA 0 (as --transparent)
  std::shared_ptr<const EnvironmentMap> map;  ///< null: the constant background
  float rotation = 0.0f;   ///< degrees about +Y (right-handed), applied to the map
  float intensity = 1.0f;  ///< scales the map's radiance
  /// Benches and tests only (no scene field or option sets it): sample the map's directions
  /// uniformly over the sphere instead of by its luminance, the baseline of bench/env_bench.
  bool uniformSampling = false;
  /// TRAY_environment "image" before io/ loads it: a path (relative to the glTF file) or a
  /// glTF image index (>= 0).
  std::string imagePath;
  int imageIndex = -1;
};

}  // namespace tray

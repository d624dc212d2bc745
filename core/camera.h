#pragma once
#include <memory>
#include <string>

#include "core/ray.h"
#include "core/transform.h"

namespace tray {

/// A camera as the scene file states it (glTF camera + its node's world transform).
/// glTF cameras look down their local -Z with +Y up.
struct CameraDesc {
  enum class Type { kPerspective, kOrthographic };
  std::string name;
  Type type = Type::kPerspective;
  float yfov = 0.8f;         ///< vertical field of view, radians
  float aspectRatio = 0.0f;  ///< width / height; 0 = not stated
  float znear = 0.0f;        ///< rays start at this distance along the view axis
  float xmag = 1.0f, ymag = 1.0f;  ///< orthographic half extents
  Transform toWorld;
};

/// Generates primary rays for raster positions (x right, y down, in pixels).
class Camera {
 public:
  virtual ~Camera() = default;
  virtual Ray generateRay(float rasterX, float rasterY) const = 0;
  /// Builds the camera for an image of width x height pixels.
  static std::unique_ptr<Camera> create(const CameraDesc& desc, int width, int height);
  /// A perspective camera framing the given bounds (used when a scene has no camera).
  static CameraDesc framing(const Bounds3& bounds, float aspectRatio);
};

}  // namespace tray

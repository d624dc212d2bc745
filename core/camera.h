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
  /// A pixel's footprint at world point p, for texture filtering: the world offsets `dx`, `dy`
  /// between the points that rays through neighbouring pixels (one raster step in x, in y)
  /// reach in the plane through p perpendicular to the view axis, and the unit direction `dir`
  /// in which camera rays travel near p. Exact for points the camera sees directly; used as an
  /// estimate everywhere else (pbrt-v4's Camera::Approximate_dp_dxy, 4th ed. §10.1.1).
  /// The default (a camera without a pixel grid) reports no spread: textures are point-sampled.
  virtual void pixelSpread(const Vec3&, Vec3& dx, Vec3& dy, Vec3& dir) const {
    dx = dy = Vec3(0.0f);
    dir = {0.0f, 0.0f, -1.0f};
  }
  /// Builds the camera for an image of width x height pixels.
  static std::unique_ptr<Camera> create(const CameraDesc& desc, int width, int height);
  /// A perspective camera framing the given bounds (used when a scene has no camera).
  static CameraDesc framing(const Bounds3& bounds, float aspectRatio);
};

}  // namespace tray

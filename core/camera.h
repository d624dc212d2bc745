#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/ray.h"
#include "core/transform.h"

namespace tray {

/// A camera as the scene file states it (glTF camera + its node's world transform).
/// glTF cameras look down their local -Z with +Y up.
struct CameraDesc {
  enum class Type { kPerspective, kOrthographic };
  std::string name;      ///< the glTF camera's name, or its node's when the camera has none
  std::string nodeName;  ///< the node that places it ("" for cameras not from a file)
  int gltfIndex = -1;    ///< its index in the file's `cameras` (-1: not from a file)
  Type type = Type::kPerspective;
  float yfov = 0.8f;         ///< vertical field of view, radians
  float aspectRatio = 0.0f;  ///< width / height; 0 = not stated
  float znear = 0.0f;        ///< rays start at this distance along the view axis
  float xmag = 1.0f, ymag = 1.0f;  ///< orthographic half extents
  /// Thin lens (TRAY_camera, --lens-radius, --focus-distance, --aperture-blades; pbrt-v4
  /// 4th ed. §5.2.3): lensRadius 0 is a pinhole.
  float lensRadius = 0.0f;     ///< aperture radius in scene units (a polygon's circumradius)
  float focusDistance = 0.0f;  ///< view depth of the plane in focus (> 0 when lensRadius > 0)
  int apertureBlades = 0;      ///< 0: a round aperture; N >= 3: a regular N-gon (bokeh shape)
  Transform toWorld;
  int node = -1;  ///< the glTF node that places it (-1: not from a file)
  /// Motion blur: toWorld at the motion steps, interpolated as a moving primitive's (core/
  /// motion.h); empty: the camera holds still over the shutter.
  std::vector<Mat4> motion;
  /// Where the camera was one frame before (time - 1/fps), for motion vectors (core/
  /// motion_vectors.h); empty: it did not move, or no previous frame was posed.
  std::optional<Transform> previousToWorld;
};

/// A uniform point on the aperture of unit circumradius from u in [0,1)^2: the unit disk
/// (blades 0, Shirley-Chiu concentric map) or a regular `blades`-gon with a vertex straight up.
Vec2 sampleAperture(const Vec2& u, int blades);

/// What a pinhole perspective camera's generateRay computes from: the SIMD camera kernel
/// (integrators/camera_batch.h) runs its one text, core/camera_lanes.h, over vectors.
struct PinholeProjection {
  Transform toWorld;
  float width = 0, height = 0;  ///< the image's size in pixels
  float znear = 0, tanHalfX = 0, tanHalfY = 0;
};

/// Generates primary rays for raster positions (x right, y down, in pixels).
class Camera {
 public:
  virtual ~Camera() = default;
  virtual Ray generateRay(float rasterX, float rasterY) const = 0;
  /// Whether the camera has a lens of non-zero radius. Pixel estimators draw a lens sample (one
  /// more 2D point after the pixel position) only then, so pinhole renders keep their numbers.
  virtual bool hasLens() const { return false; }
  /// The ray through the lens point that `lens` (in [0,1)^2) picks; a pinhole ignores it.
  virtual Ray generateLensRay(float rasterX, float rasterY, const Vec2& lens) const {
    (void)lens;
    return generateRay(rasterX, rasterY);
  }
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
  /// A perspective camera without a lens: its projection; any other camera: nothing.
  virtual std::optional<PinholeProjection> pinhole() const { return std::nullopt; }
  /// Builds the camera for an image of width x height pixels.
  static std::unique_ptr<Camera> create(const CameraDesc& desc, int width, int height);
  /// A perspective camera framing the given bounds (used when a scene has no camera).
  static CameraDesc framing(const Bounds3& bounds, float aspectRatio);
  /// The description create() built this camera from.
  const CameraDesc& desc() const { return desc_; }

 private:
  CameraDesc desc_;
};

}  // namespace tray

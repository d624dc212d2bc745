#pragma once
// The importance a camera emits (Veach 1997 §4.4 and §10.2; the structure of pbrt-v4 5.4's
// PerspectiveCamera::We / PDF_We / SampleWi): what the light-tracing strategies (t = 1) of
// bidirectional path tracing connect to, and the density of a camera ray's first hit that
// their MIS weights read.
#include <optional>

#include "core/camera.h"

namespace tray {

/// A point seen from the camera: where it lands on the image and what reaches the pixel.
struct CameraConnection {
  Vec2 raster;     ///< image position (x right, y down, in pixels)
  Vec3 wi;         ///< unit direction from the point toward the camera
  Vec3 target;     ///< the camera point the connection ends at (the pinhole; the film point)
  float distance;  ///< from the point to `target`
  /// A light vertex's radiance toward wi becomes the pixel's value times this and the cosine
  /// at the point: We cos θ / d^2 for the pinhole, sx sy for the orthographic film (below).
  float weight;
};

/// A pinhole perspective or an orthographic camera's importance, normalised per pixel so that
/// a light path's splat estimates the pixel's box-filtered value directly.
///  - Pinhole: I_j = ∫ W_j(ω) L(ω) cos θ dω with W_j = sx sy / cos^4 θ inside pixel j (sx, sy:
///    pixels per unit of the image plane at distance 1). Camera rays are uniform over the
///    image, so a ray's direction has density 1 / (A cos^3 θ) per solid angle, A the image
///    plane's area at distance 1.
///  - Orthographic: the direction is a delta; I_j = ∫ L dA_raster over the pixel, and the film
///    point is uniform with density 1/A per area (A the film's area): a first hit at a point of
///    normal n has area density |cos(n, axis)| / A, and a point y's radiance toward the film
///    reaches the pixel with weight sx sy |cos at y| (sx, sy: pixels per unit of film).
/// Thin lenses are not supported.
class CameraImportance {
 public:
  /// Nothing for a camera with a lens, or whose transform scales or shears (the maps from
  /// raster to directions and areas assume a rigid frame).
  static std::optional<CameraImportance> of(const Camera& camera, int width, int height);
  /// Where world point q is seen, or nothing when it is outside the image, behind the camera
  /// or nearer than the near plane (camera rays start there).
  std::optional<CameraConnection> connect(const Vec3& q) const;
  /// Area density at point p (geometric normal ng; zero: no cosine) of a camera ray's first
  /// hit being there, the raster position uniform over the image.
  float pdfFirst(const Vec3& p, const Vec3& ng) const;

 private:
  bool orthographic_ = false;
  Transform toWorld_;
  Vec3 position_, forward_;
  float width_ = 0, height_ = 0, znear_ = 0;
  float halfX_ = 0, halfY_ = 0;  ///< tan(fov/2) (pinhole), or xmag, ymag (orthographic)
  float area_ = 0;               ///< 4 halfX halfY: the image plane's (at distance 1) or film's
  float pixelsPerUnit2_ = 0;     ///< sx sy
};

}  // namespace tray

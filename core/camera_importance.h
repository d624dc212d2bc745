#pragma once
// The importance a pinhole perspective camera emits (Veach 1997 §4.4 and §10.2; the structure
// of pbrt-v4 5.4's PerspectiveCamera::We / PDF_We / SampleWi): what the light-tracing
// strategies (t = 1) of bidirectional path tracing connect to.
#include <optional>

#include "core/camera.h"

namespace tray {

/// A light vertex seen from the camera: where it lands on the image and what the camera's
/// importance is toward it.
struct CameraConnection {
  Vec2 raster;      ///< image position (x right, y down, in pixels)
  Vec3 wi;          ///< unit direction from the light vertex toward the camera
  float distance;   ///< from the light vertex to the camera
  float cosTheta;   ///< between the view axis and the direction out of the camera
  float importance; ///< We per pixel, see CameraImportance::importance
};

/// A pinhole perspective camera's importance, normalised per pixel: the pixel value
/// I_j = ∫ W_j(ω) L(ω) cos θ dω with W_j(ω) = sx sy / cos^4 θ inside pixel j (sx, sy: pixels
/// per unit of the image plane at distance 1) is the box-filtered mean radiance over the
/// pixel's area. Camera rays are drawn uniformly over the image, so a ray's direction has the
/// solid-angle density sx sy / (w h cos^3 θ) = 1 / (A cos^3 θ), A the image plane's area at
/// distance 1: the pdf BDPT's MIS weights read for the camera's first segment.
class CameraImportance {
 public:
  /// Nothing for a camera that is not a pinhole perspective one (thin lens, orthographic) or
  /// whose transform scales or shears (the raster-to-solid-angle map assumes a rigid frame).
  static std::optional<CameraImportance> of(const Camera& camera);
  const Vec3& position() const { return position_; }
  /// Where world point q is seen, or nothing when it is outside the image, behind the camera
  /// or nearer than the near plane (camera rays start there).
  std::optional<CameraConnection> connect(const Vec3& q) const;
  /// Solid-angle density of a camera ray direction making angle θ with the view axis.
  float pdfDir(float cosTheta) const {
    return cosTheta > 0 ? 1.0f / (planeArea_ * cosTheta * cosTheta * cosTheta) : 0.0f;
  }
  /// cos θ of a unit world direction leaving the camera.
  float cosTheta(const Vec3& w) const { return dot(w, forward_); }

 private:
  PinholeProjection proj_;
  Vec3 position_, forward_;
  float planeArea_ = 0;  ///< 4 tan(fovx/2) tan(fovy/2)
  float pixelsPerUnit2_ = 0;  ///< sx sy
};

}  // namespace tray

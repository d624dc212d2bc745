#include "core/camera_importance.h"

#include <cmath>

namespace tray {

std::optional<CameraImportance> CameraImportance::of(const Camera& camera, int width, int height) {
  const CameraDesc& d = camera.desc();
  if (camera.hasLens()) return std::nullopt;
  // A rigid frame: the three axes unit length and orthogonal.
  const Vec3 x = d.toWorld.vector({1, 0, 0}), y = d.toWorld.vector({0, 1, 0}),
             z = d.toWorld.vector({0, 0, 1});
  const float tol = 1e-3f;
  if (std::fabs(length(x) - 1) > tol || std::fabs(length(y) - 1) > tol ||
      std::fabs(length(z) - 1) > tol || std::fabs(dot(x, y)) > tol || std::fabs(dot(y, z)) > tol ||
      std::fabs(dot(x, z)) > tol)
    return std::nullopt;
  CameraImportance c;
  c.orthographic_ = d.type == CameraDesc::Type::kOrthographic;
  c.toWorld_ = d.toWorld;
  c.position_ = d.toWorld.point(Vec3(0.0f));
  c.forward_ = normalize(d.toWorld.vector({0, 0, -1}));
  c.width_ = float(width), c.height_ = float(height), c.znear_ = d.znear;
  // As core/camera.cpp builds them: the vertical extent kept, the horizontal from the image.
  c.halfY_ = c.orthographic_ ? d.ymag : std::tan(0.5f * d.yfov);
  c.halfX_ = c.halfY_ * c.width_ / c.height_;
  c.area_ = 4.0f * c.halfX_ * c.halfY_;
  c.pixelsPerUnit2_ = c.width_ * c.height_ / c.area_;
  return c;
}

std::optional<CameraConnection> CameraImportance::connect(const Vec3& q) const {
  // The inverse of generateRay: camera space, then the image plane (at depth 1) or the film,
  // then raster.
  const Vec3 qc = toWorld_.inversePoint(q);
  const float depth = -qc.z;
  if (!(depth > znear_) || !(depth > 0)) return std::nullopt;
  const float px = orthographic_ ? qc.x : qc.x / depth, py = orthographic_ ? qc.y : qc.y / depth;
  CameraConnection c;
  c.raster = {(px / halfX_ + 1.0f) * 0.5f * width_, (1.0f - py / halfY_) * 0.5f * height_};
  if (!(c.raster.x >= 0 && c.raster.x < width_ && c.raster.y >= 0 && c.raster.y < height_))
    return std::nullopt;
  if (orthographic_) {
    c.target = toWorld_.point({qc.x, qc.y, 0.0f});
    c.wi = -forward_;
    c.distance = depth;
    c.weight = pixelsPerUnit2_;
    return c;
  }
  c.target = position_;
  const Vec3 d = position_ - q;
  c.distance = length(d);
  if (!(c.distance > 0)) return std::nullopt;
  c.wi = d / c.distance;
  const float cosTheta = dot(-c.wi, forward_);
  if (!(cosTheta > 0)) return std::nullopt;
  const float c2 = cosTheta * cosTheta;
  // We = sx sy / cos^4, times cos θ / d^2.
  c.weight = pixelsPerUnit2_ / (c2 * cosTheta * c.distance * c.distance);
  return c;
}

float CameraImportance::pdfFirst(const Vec3& p, const Vec3& ng) const {
  if (orthographic_) return ng == Vec3(0.0f) ? 1.0f / area_ : std::fabs(dot(ng, forward_)) / area_;
  const Vec3 d = p - position_;
  const float d2 = dot(d, d);
  if (!(d2 > 0)) return 0.0f;
  const float dist = std::sqrt(d2);
  const float cosTheta = dot(d, forward_) / dist;
  if (!(cosTheta > 0)) return 0.0f;
  float pdf = 1.0f / (area_ * cosTheta * cosTheta * cosTheta * d2);
  if (ng != Vec3(0.0f)) pdf *= std::fabs(dot(ng, d)) / dist;
  return pdf;
}

}  // namespace tray

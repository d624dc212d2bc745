#include "core/camera_importance.h"

#include <cmath>

namespace tray {

std::optional<CameraImportance> CameraImportance::of(const Camera& camera) {
  const std::optional<PinholeProjection> p = camera.pinhole();
  if (!p) return std::nullopt;
  // A rigid frame: the three axes unit length and orthogonal.
  const Vec3 x = p->toWorld.vector({1, 0, 0}), y = p->toWorld.vector({0, 1, 0}),
             z = p->toWorld.vector({0, 0, 1});
  const float tol = 1e-3f;
  if (std::fabs(length(x) - 1) > tol || std::fabs(length(y) - 1) > tol ||
      std::fabs(length(z) - 1) > tol || std::fabs(dot(x, y)) > tol || std::fabs(dot(y, z)) > tol ||
      std::fabs(dot(x, z)) > tol)
    return std::nullopt;
  CameraImportance c;
  c.proj_ = *p;
  c.position_ = p->toWorld.point(Vec3(0.0f));
  c.forward_ = normalize(p->toWorld.vector({0, 0, -1}));
  c.planeArea_ = 4.0f * p->tanHalfX * p->tanHalfY;
  c.pixelsPerUnit2_ = p->width * p->height / c.planeArea_;
  return c;
}

std::optional<CameraConnection> CameraImportance::connect(const Vec3& q) const {
  // The inverse of generateRay (core/camera_lanes.h's perspectiveDirection): camera space,
  // then the image plane at depth 1, then raster.
  const Vec3 qc = proj_.toWorld.inversePoint(q);
  const float depth = -qc.z;
  if (!(depth > proj_.znear) || !(depth > 0)) return std::nullopt;
  const float px = qc.x / depth, py = qc.y / depth;
  CameraConnection c;
  c.raster = {(px / proj_.tanHalfX + 1.0f) * 0.5f * proj_.width,
              (1.0f - py / proj_.tanHalfY) * 0.5f * proj_.height};
  if (!(c.raster.x >= 0 && c.raster.x < proj_.width && c.raster.y >= 0 &&
        c.raster.y < proj_.height))
    return std::nullopt;
  const Vec3 d = position_ - q;
  c.distance = length(d);
  if (!(c.distance > 0)) return std::nullopt;
  c.wi = d / c.distance;
  c.cosTheta = dot(-c.wi, forward_);
  if (!(c.cosTheta > 0)) return std::nullopt;
  const float c2 = c.cosTheta * c.cosTheta;
  c.importance = pixelsPerUnit2_ / (c2 * c2);
  return c;
}

}  // namespace tray

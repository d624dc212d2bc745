#include "core/motion_vectors.h"

#include "core/motion.h"

namespace tray {

MotionVectors::MotionVectors(const Scene& scene, const CameraDesc& camera, int width, int height)
    : scene_(scene), width_(width), height_(height) {
  now_ = exrWorldToNdc(camera, width, height);
  CameraDesc before = camera;
  if (camera.previousToWorld) before.toWorld = *camera.previousToWorld;
  before_ = exrWorldToNdc(before, width, height);
}

bool MotionVectors::project(const ExrMatrix& m, const Vec3& p, Vec2& raster) const {
  // Imath's row-vector convention (core/camera_matrices.h): ndc = (p, 1) M, divided by w.
  float out[4];
  for (int j = 0; j < 4; ++j) out[j] = p.x * m[j] + p.y * m[4 + j] + p.z * m[8 + j] + m[12 + j];
  if (!(out[3] > 0)) return false;
  raster = {out[0] / out[3] * float(width_), out[1] / out[3] * float(height_)};
  return true;
}

Vec2 MotionVectors::at(const PrimaryHit& hit) const {
  if (!hit.hit || hit.primitive >= scene_.primitives.size()) return {0, 0};
  const Primitive& prim = scene_.primitives[hit.primitive];
  // The hit point on the object, found at the sample's shutter time, placed as the frame
  // shows it and as the previous frame did.
  Transform moved, scratch;
  const Transform& frame = scene_.placement(hit.primitive, hit.instance, scratch);
  const Transform* atHit = prim.motion.empty() ? &frame : placementAt(prim, hit.time, moved);
  if (!atHit) return {0, 0};
  const Vec3 local = atHit->inversePoint(hit.position);
  const Vec3 now = frame.point(local);
  Transform before = frame;  // an instance array is static: no previous placement of its own
  if (hit.primitive < scene_.previousToWorld.size() && !prim.instances)
    before.m = scene_.previousToWorld[hit.primitive];  // point() reads m only
  Vec2 a, b;
  if (!project(now_, now, a) || !project(before_, before.point(local), b)) return {0, 0};
  return {a.x - b.x, b.y - a.y};  // raster y runs down, Nuke's v up
}

}  // namespace tray

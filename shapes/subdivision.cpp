#include "shapes/subdivision.h"

#include <cmath>

namespace tray {

SubdivisionSurface::SubdivisionSurface(SubdivisionCage cage) : cage_(std::move(cage)) {
  for (const Vec3& p : cage_.positions) bounds_.extend(p);
}

const char* SubdivisionSurface::embreeOnly() const {
  return "subdivision surfaces are tessellated and intersected by Embree "
         "(RTC_GEOMETRY_TYPE_SUBDIVISION); the in-house BVH has no limit-surface evaluator (use "
         "--accel embree)";
}

bool SubdivisionSurface::shade(const Ray& local, const Hit& hit, ShapeShading& out) const {
  (void)local;
  out.ng = hit.normal;
  Vec3 n = octahedralDecode({hit.b1, hit.b2});
  // The limit normal on the tessellation's side (Embree orients both by the face winding).
  out.n = dot(n, hit.normal) < 0 ? -n : n;
  return true;
}

Vec2 octahedralEncode(const Vec3& v) {
  const float l1 = std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z);
  if (!(l1 > 0)) return {0, 0};
  Vec2 e{v.x / l1, v.y / l1};
  if (v.z < 0) {
    const float x = e.x, y = e.y;
    e.x = (1 - std::fabs(y)) * (x >= 0 ? 1.0f : -1.0f);
    e.y = (1 - std::fabs(x)) * (y >= 0 ? 1.0f : -1.0f);
  }
  return e;
}

Vec3 octahedralDecode(Vec2 e) {
  Vec3 v{e.x, e.y, 1 - std::fabs(e.x) - std::fabs(e.y)};
  if (v.z < 0) {
    const float x = v.x, y = v.y;
    v.x = (1 - std::fabs(y)) * (x >= 0 ? 1.0f : -1.0f);
    v.y = (1 - std::fabs(x)) * (y >= 0 ? 1.0f : -1.0f);
  }
  return normalize(v);
}

}  // namespace tray

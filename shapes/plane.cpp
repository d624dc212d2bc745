#include "shapes/plane.h"

namespace tray {

Bounds3 Plane::bounds() const { return {{-kInfinity, 0.0f, -kInfinity}, {kInfinity, 0.0f, kInfinity}}; }

bool Plane::intersect(const Ray& ray, Hit& hit) const {
  // A ray parallel to the plane (d.y == 0) never crosses it; t is then inf or NaN and both
  // fail the range test below.
  float t = -ray.o.y / ray.d.y;
  if (!(t > ray.tmin && t < ray.tmax)) return false;
  hit.t = t;
  hit.normal = {0.0f, 1.0f, 0.0f};
  hit.uv = {ray.o.x + t * ray.d.x, ray.o.z + t * ray.d.z};
  return true;
}

void Plane::uvDerivatives(const Vec3&, const Vec3&, Vec3& dpdu, Vec3& dpdv) const {
  dpdu = {1.0f, 0.0f, 0.0f};
  dpdv = {0.0f, 0.0f, 1.0f};
}

void Plane::intervals(const Ray& ray, std::vector<Interval>& out) const {
  const Vec3 up{0.0f, 1.0f, 0.0f};
  if (ray.d.y == 0.0f) {
    if (ray.o.y <= 0.0f) out.push_back({{-kInfinity, up, {}, -1}, {kInfinity, up, {}, -1}});
    return;
  }
  float t = -ray.o.y / ray.d.y;
  Vec2 uv{ray.o.x + t * ray.d.x, ray.o.z + t * ray.d.z};
  if (ray.d.y > 0.0f)  // moving up: inside before the crossing
    out.push_back({{-kInfinity, up, {}, -1}, {t, up, uv, -1}});
  else
    out.push_back({{t, up, uv, -1}, {kInfinity, up, {}, -1}});
}

}  // namespace tray

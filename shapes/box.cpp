#include "shapes/box.h"

namespace tray {

Bounds3 Box::bounds() const { return {lo_, hi_}; }

bool Box::slabs(const Ray& ray, float& t0, float& t1, int& axis0, int& axis1) const {
  // Kay-Kajiya slabs. An axis the ray is parallel to is handled explicitly: 0 * inf would give
  // NaN when the origin lies exactly on that slab's boundary.
  t0 = -kInfinity;
  t1 = kInfinity;
  axis0 = axis1 = 0;
  for (int a = 0; a < 3; ++a) {
    if (ray.d[a] == 0.0f) {
      if (ray.o[a] < lo_[a] || ray.o[a] > hi_[a]) return false;
      continue;
    }
    float inv = 1.0f / ray.d[a];
    float tn = (lo_[a] - ray.o[a]) * inv, tf = (hi_[a] - ray.o[a]) * inv;
    if (tn > tf) std::swap(tn, tf);
    if (tn > t0) t0 = tn, axis0 = a;
    if (tf < t1) t1 = tf, axis1 = a;
  }
  return t0 <= t1;
}

Crossing Box::crossing(const Ray& ray, float t, int axis, bool entering) const {
  Crossing c;
  c.t = t;
  float s = ray.d[axis] > 0 ? 1.0f : -1.0f;
  c.normal[axis] = entering ? -s : s;
  Vec3 p = ray.o + t * ray.d;
  int u = (axis + 1) % 3, v = (axis + 2) % 3;
  Vec3 size = hi_ - lo_;
  c.uv = {(p[u] - lo_[u]) / size[u], (p[v] - lo_[v]) / size[v]};
  return c;
}

bool Box::intersect(const Ray& ray, Hit& hit) const {
  float t0, t1;
  int a0, a1;
  if (!slabs(ray, t0, t1, a0, a1)) return false;
  Crossing c;
  if (t0 > ray.tmin && t0 < ray.tmax)
    c = crossing(ray, t0, a0, true);
  else if (t1 > ray.tmin && t1 < ray.tmax)
    c = crossing(ray, t1, a1, false);  // the ray starts inside: its exit
  else
    return false;
  hit.t = c.t;
  hit.normal = c.normal;
  hit.uv = c.uv;
  return true;
}

void Box::intervals(const Ray& ray, std::vector<Interval>& out) const {
  float t0, t1;
  int a0, a1;
  if (!slabs(ray, t0, t1, a0, a1)) return;
  out.push_back({crossing(ray, t0, a0, true), crossing(ray, t1, a1, false)});
}

Vec3 Box::refine(const Vec3& p) const {
  // Snap the coordinate of the nearest face exactly onto it.
  int bestAxis = 0;
  float bestDist = kInfinity, bestValue = 0;
  for (int a = 0; a < 3; ++a)
    for (float face : {lo_[a], hi_[a]}) {
      float dist = std::fabs(p[a] - face);
      if (dist < bestDist) bestDist = dist, bestAxis = a, bestValue = face;
    }
  Vec3 r = p;
  r[bestAxis] = bestValue;
  return r;
}

}  // namespace tray

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
  c.uv = faceUv(ray.o + t * ray.d, axis, c.normal[axis]);
  return c;
}

Box::FaceAxes Box::faceAxes(int axis, float sign) {
  // right = up x n for a viewer outside looking along -n; up = +Y on side faces.
  if (axis == 0) return {2, 1, -sign, 1.0f};
  if (axis == 2) return {0, 1, sign, 1.0f};
  return {0, 2, 1.0f, -sign};  // top face: up is -Z, bottom face: +Z
}

Vec2 Box::faceUv(const Vec3& p, int axis, float sign) const {
  FaceAxes f = faceAxes(axis, sign);
  Vec3 size = hi_ - lo_;
  float u = f.rightSign > 0 ? p[f.right] - lo_[f.right] : hi_[f.right] - p[f.right];
  float v = f.upSign > 0 ? hi_[f.up] - p[f.up] : p[f.up] - lo_[f.up];
  return {u / size[f.right], v / size[f.up]};
}

void Box::uvDerivatives(const Vec3&, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const {
  Vec3 an = abs(n);
  int axis = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  FaceAxes f = faceAxes(axis, n[axis] >= 0 ? 1.0f : -1.0f);
  Vec3 size = hi_ - lo_;
  dpdu = dpdv = Vec3(0.0f);
  dpdu[f.right] = f.rightSign * size[f.right];
  dpdv[f.up] = -f.upSign * size[f.up];
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

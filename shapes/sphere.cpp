#include "shapes/sphere.h"

namespace tray {

Bounds3 Sphere::bounds() const { return {Vec3(-radius_), Vec3(radius_)}; }

bool Sphere::roots(const Ray& ray, float& t0, float& t1) const {
  // Haines et al., "Precision Improvements for Ray/Sphere Intersection", Ray Tracing Gems
  // ch. 7: the discriminant from the squared distance of the line to the centre avoids the
  // cancellation of b^2 - ac, and the roots come from the stable quadratic form.
  const Vec3& o = ray.o;
  const Vec3& d = ray.d;
  float a = dot(d, d);
  float b = dot(o, d);
  float c = dot(o, o) - radius_ * radius_;
  Vec3 l = o - (b / a) * d;
  float disc = a * (radius_ * radius_ - dot(l, l));
  if (!(disc >= 0.0f)) return false;  // also rejects NaN
  float q = -(b + std::copysign(std::sqrt(disc), b));
  if (q == 0.0f) {  // ray from the centre along... only when b == 0 and disc == 0 (degenerate)
    t0 = t1 = 0.0f;
    return c <= 0.0f;
  }
  t0 = c / q;
  t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  return true;
}

Vec2 Sphere::uvAt(const Vec3& p) const {
  float phi = std::atan2(p.x, p.z);
  if (phi < 0) phi += 2.0f * kPi;
  float cosTheta = std::clamp(p.y / radius_, -1.0f, 1.0f);
  return {phi / (2.0f * kPi), std::acos(cosTheta) / kPi};
}

void Sphere::uvDerivatives(const Vec3& p, const Vec3&, Vec3& dpdu, Vec3& dpdv) const {
  // p = r (sin(theta) sin(phi), cos(theta), sin(theta) cos(phi)) with phi = 2 pi u,
  // theta = pi v; dp/du vanishes at the poles.
  float phi = std::atan2(p.x, p.z);
  float theta = std::acos(std::clamp(p.y / radius_, -1.0f, 1.0f));
  dpdu = 2.0f * kPi * Vec3(p.z, 0.0f, -p.x);
  float c = std::cos(theta), sn = std::sin(theta);
  dpdv = kPi * radius_ * Vec3(c * std::sin(phi), -sn, c * std::cos(phi));
}

bool Sphere::intersect(const Ray& ray, Hit& hit) const {
  float t0, t1;
  if (!roots(ray, t0, t1)) return false;
  // The far root is the exit when the ray starts inside (RenderKit/embree#269).
  float t = t0 > ray.tmin ? t0 : t1;
  if (!(t > ray.tmin && t < ray.tmax)) return false;
  Vec3 p = ray.o + t * ray.d;
  hit.t = t;
  hit.normal = p;
  hit.uv = uvAt(p);
  return true;
}

void Sphere::intervals(const Ray& ray, std::vector<Interval>& out) const {
  float t0, t1;
  if (!roots(ray, t0, t1)) return;
  Vec3 p0 = ray.o + t0 * ray.d, p1 = ray.o + t1 * ray.d;
  out.push_back({{t0, p0, uvAt(p0), -1}, {t1, p1, uvAt(p1), -1}});
}

Vec3 Sphere::refine(const Vec3& p) const {
  float len = length(p);
  return len > 0 ? p * (radius_ / len) : p;
}

}  // namespace tray

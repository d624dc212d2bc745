#include <cmath>

#include "core/error.h"
#include "shapes/quadric.h"

namespace tray {

Disk::Disk(float radius, float innerRadius) : radius_(radius), inner_(innerRadius) {
  if (!(radius > 0 && std::isfinite(radius) && innerRadius >= 0 && innerRadius < radius))
    throw Error("disk: needs radius > innerRadius >= 0");
}

Bounds3 Disk::bounds() const {
  return {Vec3(-radius_, 0, -radius_), Vec3(radius_, 0, radius_)};
}

Vec2 Disk::uvAt(const Vec3& p) const {
  float phi = std::atan2(p.x, p.z);
  if (phi < 0) phi += 2.0f * kPi;
  const float rho = std::sqrt(p.x * p.x + p.z * p.z);
  return {phi / (2.0f * kPi), (radius_ - rho) / (radius_ - inner_)};
}

bool Disk::intersect(const Ray& ray, Hit& hit) const {
  if (ray.d.y == 0.0f) return false;
  const double t = -double(ray.o.y) / double(ray.d.y);
  const float tf = float(t);
  if (!(tf > ray.tmin && tf < ray.tmax)) return false;
  const double x = ray.o.x + t * ray.d.x, z = ray.o.z + t * ray.d.z, r2 = x * x + z * z;
  if (r2 > double(radius_) * radius_ || r2 < double(inner_) * inner_) return false;
  hit.t = tf;
  hit.normal = Vec3(0, 1, 0);
  hit.uv = uvAt({float(x), 0.0f, float(z)});
  return true;
}

void Disk::uvDerivatives(const Vec3& p, const Vec3&, Vec3& dpdu, Vec3& dpdv) const {
  dpdu = 2.0f * kPi * Vec3(p.z, 0.0f, -p.x);
  const float rho = std::sqrt(p.x * p.x + p.z * p.z);
  dpdv = rho > 0 ? (-(radius_ - inner_) / rho) * Vec3(p.x, 0.0f, p.z) : Vec3(0.0f);
}

float Disk::area(const Transform& toWorld) const {
  return kPi * (radius_ * radius_ - inner_ * inner_) * areaScale(toWorld, Vec3(0, 1, 0));
}

std::optional<ShapeSample> Disk::sampleArea(const Transform& toWorld, Vec2 u) const {
  const float a = area(toWorld);
  if (!(a > 0) || !std::isfinite(a)) return std::nullopt;
  // Uniform in the annulus: rho^2 uniform in [inner^2, radius^2]; an affine map scales every
  // area element of a plane alike, so the world density is uniform too.
  const float rho = std::sqrt(inner_ * inner_ + u.y * (radius_ * radius_ - inner_ * inner_));
  const float phi = 2.0f * kPi * u.x;
  ShapeSample s;
  s.p = toWorld.point({rho * std::sin(phi), 0.0f, rho * std::cos(phi)});
  s.n = normalize(toWorld.normal({0, 1, 0}));
  s.pdf = 1.0f / a;
  return s;
}

}  // namespace tray

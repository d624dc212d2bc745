// Quadric sampling for emitters (core/shape.h's sampling interface): the cylinder and the cone,
// with their caps when capped, uniform by area.
#include <cmath>

#include "shapes/quadric.h"

namespace tray {

namespace {

float meanScale2(const Transform& toWorld) {
  const float s = (length(toWorld.vector({1, 0, 0})) + length(toWorld.vector({0, 1, 0})) +
                   length(toWorld.vector({0, 0, 1}))) /
                  3.0f;
  return s * s;
}

}  // namespace

/// Object-space areas: side, cap at y = 0, cap at y = height (0 for absent caps).
static void partAreas(const Quadric& q, float out[3]) {
  const float r = q.radius(), h = q.height();
  out[0] = out[1] = out[2] = 0;
  if (q.kind() == Quadric::Kind::kCylinder) {
    out[0] = 2 * kPi * r * h;
    if (q.capped()) out[1] = out[2] = kPi * r * r;
  } else if (q.kind() == Quadric::Kind::kCone) {
    out[0] = kPi * r * std::sqrt(r * r + h * h);
    if (q.capped()) out[1] = kPi * r * r;
  }
}

float Quadric::area(const Transform& toWorld) const {
  float a[3];
  partAreas(*this, a);
  return (a[0] + a[1] + a[2]) * meanScale2(toWorld);
}

std::optional<ShapeSample> Quadric::sampleArea(const Transform& toWorld, Vec2 u) const {
  float a[3];
  partAreas(*this, a);
  const float total = a[0] + a[1] + a[2], world = total * meanScale2(toWorld);
  if (!(total > 0) || !(world > 0) || !std::isfinite(world)) return std::nullopt;
  // The part with u.x, its remainder reused (pbrt-v4 A.1), then the angle.
  float target = u.x * total;
  int part = 0;
  while (part < 2 && target >= a[part]) target -= a[part++];
  const float w = std::min(a[part] > 0 ? target / a[part] : 0.0f, 0.99999994f);
  const float phi = 2 * kPi * u.y, sp = std::sin(phi), cp = std::cos(phi);
  Vec3 p, n;
  if (part == 0) {
    // Cylinder: y uniform. Cone: the area element grows with the distance from the apex, so
    // that distance goes as sqrt(w): rho = r sqrt(w), y = h (1 - sqrt(w)).
    float y = w * height_, rho = radius_;
    if (kind_ == Kind::kCone) {
      const float k = std::sqrt(w);
      rho = radius_ * k, y = height_ * (1 - k);
    }
    p = {rho * sp, y, rho * cp};
    // The cone's normal depends on the angle only (defined at the apex too).
    n = kind_ == Kind::kCone ? Vec3(height_ * sp, radius_, height_ * cp) : sideNormal(p);
  } else {
    const float rho = radius_ * std::sqrt(w);
    p = {rho * sp, part == 1 ? 0.0f : height_, rho * cp};
    n = {0, part == 1 ? -1.0f : 1.0f, 0};
  }
  ShapeSample s;
  s.p = toWorld.point(p);
  s.n = normalize(toWorld.normal(n));
  s.pdf = 1.0f / world;
  return s;
}

}  // namespace tray

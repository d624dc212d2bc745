#pragma once
#include "core/shape.h"

namespace tray {

/// Sphere of the given radius centred at the object-space origin. uv: latitude-longitude
/// (u = azimuth around +Y / 2pi, v = polar angle from +Y / pi).
class Sphere final : public Shape {
 public:
  explicit Sphere(float radius = 1.0f) : radius_(radius) {}
  Bounds3 bounds() const override;
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray& ray, std::vector<Interval>& out) const override;
  void uvDerivatives(const Vec3& p, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const override;
  Vec3 refine(const Vec3& p) const override;
  float radius() const { return radius_; }
  /// Texture coordinates of an object-space surface point.
  Vec2 uvAt(const Vec3& p) const;

 private:
  /// Both roots of |o + t d|^2 = r^2, t0 <= t1; false if the line misses.
  bool roots(const Ray& ray, float& t0, float& t1) const;
  float radius_;
};

}  // namespace tray

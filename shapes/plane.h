#pragma once
#include "core/shape.h"

namespace tray {

/// The infinite plane y = 0 of object space, normal +Y. As a CSG solid: the half-space y <= 0.
/// uv: planar (x, z), tiling with period 1.
class Plane final : public Shape {
 public:
  Bounds3 bounds() const override;
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray& ray, std::vector<Interval>& out) const override;
  void uvDerivatives(const Vec3& p, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const override;
  Vec3 refine(const Vec3& p) const override { return {p.x, 0.0f, p.z}; }
};

}  // namespace tray

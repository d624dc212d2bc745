#pragma once
#include "shapes/shape.h"

namespace tray {

/// Axis-aligned box [lo, hi] in object space. uv: per face, the face's two other axes mapped
/// to [0, 1].
class Box final : public Shape {
 public:
  Box(const Vec3& lo = Vec3(-1.0f), const Vec3& hi = Vec3(1.0f)) : lo_(lo), hi_(hi) {}
  Bounds3 bounds() const override;
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray& ray, std::vector<Interval>& out) const override;
  Vec3 refine(const Vec3& p) const override;

 private:
  /// Slab test over the whole line; false if the line misses. Axis of entry/exit returned.
  bool slabs(const Ray& ray, float& t0, float& t1, int& axis0, int& axis1) const;
  Crossing crossing(const Ray& ray, float t, int axis, bool entering) const;
  Vec3 lo_, hi_;
};

}  // namespace tray

#pragma once
#include "core/shape.h"

namespace tray {

/// Axis-aligned box [lo, hi] in object space. uv: per face, [0, 1]^2 over the face, oriented
/// so that an image appears upright and unmirrored seen from outside: v = 0 at the top edge
/// (+Y for the four side faces; the far -Z edge for the top face, +Z for the bottom) and u
/// growing to the viewer's right.
class Box final : public Shape {
 public:
  Box(const Vec3& lo = Vec3(-1.0f), const Vec3& hi = Vec3(1.0f)) : lo_(lo), hi_(hi) {}
  Bounds3 bounds() const override;
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray& ray, std::vector<Interval>& out) const override;
  void uvDerivatives(const Vec3& p, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const override;
  Vec3 refine(const Vec3& p) const override;
  /// Sum of the six faces' world areas (each an object-space rectangle scaled by the
  /// transform, core/shape.h areaScale).
  float area(const Transform& toWorld) const override;
  /// A face chosen by world area, then a uniform point on it: uniform over the whole surface.
  std::optional<ShapeSample> sampleArea(const Transform& toWorld, Vec2 u) const override;

 private:
  /// World area of each face, in the order axis 0..2, sign - then + (index 2 axis + side).
  void faceAreas(const Transform& toWorld, float out[6]) const;
  /// Slab test over the whole line; false if the line misses. Axis of entry/exit returned.
  bool slabs(const Ray& ray, float& t0, float& t1, int& axis0, int& axis1) const;
  Crossing crossing(const Ray& ray, float t, int axis, bool entering) const;
  /// The face's right (u) and up axes with their signs, for the face normal to `axis` on the
  /// `sign` (+1 / -1) side.
  struct FaceAxes {
    int right, up;
    float rightSign, upSign;
  };
  static FaceAxes faceAxes(int axis, float sign);
  Vec2 faceUv(const Vec3& p, int axis, float sign) const;
  Vec3 lo_, hi_;
};

}  // namespace tray

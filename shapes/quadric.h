#pragma once
#include <string>

#include "core/shape.h"

namespace tray {

/// A quadric of revolution about the object-space y axis (pbrt-v3's cylinder, cone,
/// paraboloid and hyperboloid, 3.2 - 3.5, about y instead of z): the surface x^2 + z^2 =
/// rho^2(y) = a y^2 + b y + c for y in [0, height]. Capped, it is the closed solid
/// {0 <= y <= height, x^2 + z^2 <= rho^2(y)}: the lateral surface plus the disks closing its
/// ends (where rho > 0), usable as a CSG operand. Open, it is the lateral surface alone: not a
/// solid (intervals() reports nothing and CSG refuses it, see isSolid()).
///
/// uv: u = angle around +Y / 2pi (0 on +Z, as the sphere's), v = y / height on the side; on a
/// cap v = distance from the axis / the cap's radius.
class Quadric final : public Shape {
 public:
  enum class Kind { kCylinder, kCone, kParaboloid, kHyperboloid };
  /// Cylinder of `radius`; cone from `radius` at y = 0 to its apex at y = height; paraboloid
  /// from its apex at y = 0 to `radius` at y = height; hyperboloid of one sheet of `radius` at
  /// both ends and `waist` (0 <= waist < radius; 0: a double cone) at y = height / 2.
  /// Throws tray::Error on non-positive sizes.
  Quadric(Kind kind, float radius, float height, bool capped, float waist = 0.0f);

  Bounds3 bounds() const override;
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray& ray, std::vector<Interval>& out) const override;
  bool isSolid() const override { return capped_; }
  void uvDerivatives(const Vec3& p, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const override;
  Vec3 refine(const Vec3& p) const override;
  /// Cylinder and cone (with their caps when capped): the exact area scaled by the mean axis
  /// scale squared (similarity placement, as the sphere). Paraboloid and hyperboloid: 0, not
  /// sampled (an emissive one is found by BSDF sampling only).
  float area(const Transform& toWorld) const override;
  std::optional<ShapeSample> sampleArea(const Transform& toWorld, Vec2 u) const override;

  Kind kind() const { return kind_; }
  bool capped() const { return capped_; }
  float radius() const { return radius_; }
  float height() const { return height_; }
  /// rho^2 at height y.
  double rho2(double y) const { return (a_ * y + b_) * y + c_; }
  /// Outward normal of the lateral surface at p (unnormalised).
  Vec3 sideNormal(const Vec3& p) const;

 private:
  /// Crossings of the whole line (ray t), in order, with whether each is a cap crossing; for
  /// a capped solid they pair into intervals, for an open one each is a crossing of the side.
  int crossings(const Ray& ray, double t[4], int cap[4]) const;
  Crossing crossingAt(const Ray& ray, double t, int cap) const;
  float capRadius(int cap) const;  ///< cap 0: y = 0, cap 1: y = height
  Vec2 uvAt(const Vec3& p, int cap) const;

  Kind kind_;
  float radius_, height_, waist_;
  bool capped_;
  double a_, b_, c_;
};

/// The disk (annulus: inner radius >= 0) in the y = 0 plane of object space, normal +Y: an open
/// surface, not a solid (pbrt-v3 3.4, about y). uv: u = angle around +Y / 2pi, v = (radius -
/// distance from the axis) / (radius - inner radius), as pbrt's. Sampled uniformly by area
/// (exact under any affine placement).
class Disk final : public Shape {
 public:
  Disk(float radius = 1.0f, float innerRadius = 0.0f);
  Bounds3 bounds() const override;
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray&, std::vector<Interval>&) const override {}
  bool isSolid() const override { return false; }
  void uvDerivatives(const Vec3& p, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const override;
  Vec3 refine(const Vec3& p) const override { return {p.x, 0.0f, p.z}; }
  float area(const Transform& toWorld) const override;
  std::optional<ShapeSample> sampleArea(const Transform& toWorld, Vec2 u) const override;
  Vec2 uvAt(const Vec3& p) const;

 private:
  float radius_, inner_;
};

}  // namespace tray

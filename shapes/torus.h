#pragma once
#include "core/shape.h"

namespace tray {

/// How Torus finds the roots of its quartic (docs/shapes.md has the measured failures).
enum class QuarticSolver {
  kIsolated,            ///< shipped: isolation by derivatives, bracketed Newton (robust)
  kClosedForm,          ///< Ferrari / Cardano as published (Graphics Gems I): loses hits
  kClosedFormPolished,  ///< the same, each root polished by Newton: still loses hits
};

/// A ring torus about the object-space y axis: the circle of radius R (major) in the xz plane,
/// swept by a disk of radius r (minor), R > r > 0; the solid
/// (|p|^2 + R^2 - r^2)^2 <= 4 R^2 (x^2 + z^2). uv: u = angle around +Y / 2pi (0 on +Z, as the
/// sphere's), v = angle around the tube / 2pi (0 on the outer equator, 1/4 on top).
class Torus final : public Shape {
 public:
  Torus(float majorRadius = 1.0f, float minorRadius = 0.25f,
        QuarticSolver solver = QuarticSolver::kIsolated);
  Bounds3 bounds() const override;
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray& ray, std::vector<Interval>& out) const override;
  void uvDerivatives(const Vec3& p, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const override;
  Vec3 refine(const Vec3& p) const override;
  /// 4 pi^2 R r, scaled by the mean axis scale squared (analytic shapes are placed by
  /// similarity transforms, as the sphere).
  float area(const Transform& toWorld) const override;
  /// Uniform by area: u around the ring, the tube angle by inverting its cdf (the area element
  /// is proportional to R + r cos v).
  std::optional<ShapeSample> sampleArea(const Transform& toWorld, Vec2 u) const override;

  float majorRadius() const { return R_; }
  float minorRadius() const { return r_; }
  Vec2 uvAt(const Vec3& p) const;
  /// Outward normal at a surface point (unnormalised): from the tube's centre circle to p.
  Vec3 normalAt(const Vec3& p) const;
  /// Every crossing of the whole line o + t d with the surface, ascending (0, 2 or 4 of them,
  /// pairs entering / leaving), in the ray's t, solved in double with the chosen solver.
  int lineRoots(const Ray& ray, double t[4]) const;
  /// The quartic in s of the line o + s u (u unit, o double) : its coefficients c[0..4].
  void quartic(const double o[3], const double u[3], double c[5]) const;

 private:
  float R_, r_;
  QuarticSolver solver_;
};

}  // namespace tray

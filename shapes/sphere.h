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
  float area(const Transform& toWorld) const override;
  std::optional<ShapeSample> sampleArea(const Transform& toWorld, Vec2 u) const override;
  /// From outside: uniform in the cone of directions the sphere subtends (pbrt-v4 6.2.4), so
  /// every sample hits it and the pdf is the constant 1 / (2 pi (1 - cos theta_max)). From
  /// inside: no samples (a sphere emits outwards; BSDF sampling still finds its inside).
  std::optional<ShapeSample> sample(const ShapeSampleContext& ctx, Vec2 u) const override;
  float pdf(const ShapeSampleContext& ctx, const Vec3& p, const Vec3& n) const override;
  float radius() const { return radius_; }
  /// Texture coordinates of an object-space surface point.
  Vec2 uvAt(const Vec3& p) const;

 private:
  /// Both roots of |o + t d|^2 = r^2, t0 <= t1; false if the line misses.
  bool roots(const Ray& ray, float& t0, float& t1) const;
  /// Radius in world space: analytic spheres are placed by similarity transforms; the mean
  /// axis scale.
  float worldRadius(const Transform& toWorld) const;
  /// 1 - cos theta_max of the cone the world sphere (centre c, radius r) subtends from ref,
  /// without cancellation; <= 0 inside.
  static float oneMinusCosMax(const Vec3& c, float r, const Vec3& ref);
  float radius_;
};

}  // namespace tray

#pragma once
#include <vector>

#include "core/bounds.h"
#include "core/hit.h"
#include "core/ray.h"

namespace tray {

/// A point where a ray crosses a solid's boundary (object space).
struct Crossing {
  float t = 0;
  Vec3 normal;       ///< outward geometric normal of the surface crossed
  Vec2 uv;
  int material = -1;  ///< -1: the shape's own material
};

/// A stretch of the ray's line inside a solid: [enter, exit]. Either end may be infinite.
struct Interval {
  Crossing enter, exit;
};

/// An analytic shape in its own object space. The primitive's transform places it in the world;
/// rays arrive already transformed (direction not normalised, so t is the world t).
class Shape {
 public:
  virtual ~Shape() = default;
  /// Object-space bounds; may be infinite (a plane).
  virtual Bounds3 bounds() const = 0;
  /// Nearest crossing with t in (ray.tmin, ray.tmax); fills hit.t, hit.normal (outward,
  /// unnormalised allowed), hit.uv. Must find the exit when the ray starts inside.
  virtual bool intersect(const Ray& ray, Hit& hit) const = 0;
  /// Every interval of the whole line o + t d (t from -inf to inf) inside the solid, sorted by t.
  /// Used by CSG; a plane is the half-space y <= 0.
  virtual void intervals(const Ray& ray, std::vector<Interval>& out) const = 0;
  /// Projects a computed hit point back onto the surface, to tighten the ray-offset error.
  virtual Vec3 refine(const Vec3& p) const { return p; }
  /// Object-space derivatives of the surface point with respect to its uv at surface point p
  /// with outward normal n, for texture filtering and normal-map tangent frames. The default
  /// (shapes without a parameterisation, e.g. CSG results) is zero: textures are then
  /// point-sampled and tangent frames arbitrary.
  virtual void uvDerivatives(const Vec3& p, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const {
    (void)p, (void)n;
    dpdu = dpdv = Vec3(0.0f);
  }
};

}  // namespace tray

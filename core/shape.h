#pragma once
#include <optional>
#include <vector>

#include "core/bounds.h"
#include "core/hit.h"
#include "core/ray.h"
#include "core/transform.h"

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

/// A point on a shape's surface, in world space (pbrt-v4 6.1.4's ShapeSample).
struct ShapeSample {
  Vec3 p;         ///< the point
  Vec3 n;         ///< unit outward normal there
  Vec3 wi;        ///< Shape::sample(ctx, u) only: unit direction from ctx.p towards p
  float pdf = 0;  ///< per world area (sampleArea) or per solid angle at ctx.p (sample)
};

/// Where a shape is sampled from, and how it is placed (pbrt-v4's ShapeSampleContext; TRay's
/// shapes live in object space, so the primitive's transform travels with the query).
struct ShapeSampleContext {
  const Transform& toWorld;
  Vec3 p;  ///< the world-space reference point
};

/// Factor by which toWorld scales the area of a surface element with object-space unit normal
/// n: |det M| |M^-T n| (Nanson's formula).
float areaScale(const Transform& toWorld, const Vec3& n);

/// What Shape::shade adds to a hit, in object space (unnormalised allowed).
struct ShapeShading {
  Vec3 ng;       ///< outward geometric normal
  Vec3 n;        ///< shading normal
  Vec3 tangent;  ///< a fibre's direction (curves); zero elsewhere
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
  /// Whether the shape bounds a solid, so that intervals() is meaningful and it may be a CSG
  /// operand. Open surfaces (a disk, an uncapped cylinder) are not: their intervals() is empty
  /// and Csg refuses them by name.
  virtual bool isSolid() const { return true; }
  /// Shapes only Embree intersects (curves, subdivision surfaces: shapes/curves.h,
  /// shapes/subdivision.h): why, in a few words; nullptr for the others. Every other
  /// accelerator refuses a scene holding one, naming it (docs/curves-subdivision.md).
  virtual const char* embreeOnly() const { return nullptr; }
  /// The normals (and a fibre's tangent) at a hit, for shapes whose hit.normal does not say it
  /// all (curves: the fibre's axis; flat ribbons' round-fibre normal). false: hit.normal is both
  /// normals. local: the ray in object space.
  virtual bool shade(const Ray& local, const Hit& hit, ShapeShading& out) const {
    (void)local, (void)hit, (void)out;
    return false;
  }
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

  // Sampling, for emitters made of shapes (lights/area_light.h); pbrt-v4 6.1's Shape::Area,
  // Sample(u), Sample(ctx, u) and PDF(ctx, wi). A shape that cannot be sampled (infinite, or
  // CSG) keeps the defaults: area 0 and no samples; its emission is then found by BSDF
  // sampling alone, with MIS weight 1.

  /// World-space surface area when placed by toWorld; 0: not samplable.
  virtual float area(const Transform& toWorld) const {
    (void)toWorld;
    return 0.0f;
  }
  /// A point uniform by world area (pdf = 1 / area(toWorld)); nullopt when not samplable.
  virtual std::optional<ShapeSample> sampleArea(const Transform& toWorld, Vec2 u) const {
    (void)toWorld, (void)u;
    return std::nullopt;
  }
  /// A point as seen from ctx.p, pdf per solid angle there, wi filled. The default converts an
  /// area sample (pdf-to-solid-angle factor d^2 / |cos|, pbrt-v4 6.1.4); shapes with a better
  /// strategy (a sphere's cone, pbrt-v4 6.2.4) override it together with pdf().
  virtual std::optional<ShapeSample> sample(const ShapeSampleContext& ctx, Vec2 u) const;
  /// The solid-angle pdf with which sample(ctx, u) returns the point p with unit normal n (the
  /// point where a direction from ctx.p first meets the shape: pbrt's PDF(ctx, wi) with the
  /// intersection already found by the caller).
  virtual float pdf(const ShapeSampleContext& ctx, const Vec3& p, const Vec3& n) const;
};

}  // namespace tray

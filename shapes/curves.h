#pragma once
#include <cstdint>
#include <vector>

#include "core/shape.h"

namespace tray {

/// A control point of a curve: position and radius (Embree's RTC_FORMAT_FLOAT4 layout).
struct CurvePoint {
  Vec3 p;
  float radius = 0;
};

/// The cubic basis of a curve's segments (Embree's RTC_GEOMETRY_TYPE_*_CURVE).
enum class CurveBasis { kBezier, kBSpline };
/// Round: a swept tube (a real surface, seen up close). Flat: a ribbon that always faces the
/// ray (cheaper; the hair BSDF reads its v across the ribbon as the fibre offset h).
enum class CurveShape { kRound, kFlat };

/// Hair and fur: cubic curve segments with per-control-point radius, intersected by Embree's
/// own curve primitives (docs/curves-subdivision.md; TRAY_curves). Each segment is the 4
/// control points from its index on; a B-spline strand of n points has n - 3 segments, a
/// Bezier strand 3k + 1 points and k segments. Embree only: the in-house BVH has no curve
/// intersector (embreeOnly). Hits carry the segment in Hit::triangle, Embree's u (along the
/// segment) and v (across a ribbon) in Hit::uv, and Embree's Ng in Hit::normal (round: the
/// tube's normal; flat: the curve's tangent).
class Curves final : public Shape {
 public:
  Curves(CurveBasis basis, CurveShape shape, std::vector<CurvePoint> points,
         std::vector<uint32_t> segments);
  CurveBasis basis() const { return basis_; }
  CurveShape shape() const { return shape_; }
  const std::vector<CurvePoint>& points() const { return points_; }
  const std::vector<uint32_t>& segments() const { return segments_; }

  Bounds3 bounds() const override { return bounds_; }
  /// Never called: every accelerator but Embree refuses curves (embreeOnly).
  bool intersect(const Ray&, Hit&) const override { return false; }
  void intervals(const Ray&, std::vector<Interval>&) const override {}
  bool isSolid() const override { return false; }
  const char* embreeOnly() const override;
  bool shade(const Ray& local, const Hit& hit, ShapeShading& out) const override;

  /// Position, derivative d/du and radius of segment `segment` at u in [0, 1].
  void evaluate(uint32_t segment, float u, Vec3& p, Vec3& dpdu, float& radius) const;

 private:
  CurveBasis basis_;
  CurveShape shape_;
  std::vector<CurvePoint> points_;
  std::vector<uint32_t> segments_;
  Bounds3 bounds_;
};

/// The segment start indices of strands of the given point counts laid end to end: n - 3 per
/// B-spline strand, (n - 1) / 3 per Bezier strand (whose n must be 3k + 1). Empty when a count
/// does not fit the basis (the caller names the strand).
std::vector<uint32_t> curveSegmentsOfStrands(CurveBasis basis, const std::vector<uint32_t>& counts,
                                             size_t* badStrand);

}  // namespace tray

#include "shapes/curves.h"

#include <algorithm>
#include <cmath>

namespace tray {

Curves::Curves(CurveBasis basis, CurveShape shape, std::vector<CurvePoint> points,
               std::vector<uint32_t> segments)
    : basis_(basis), shape_(shape), points_(std::move(points)), segments_(std::move(segments)) {
  // Both bases keep each segment inside its control points' convex hull, and the radius is
  // interpolated by the same non-negative weights: the hull grown by the largest radius bounds
  // the swept tube.
  float rMax = 0;
  for (const CurvePoint& c : points_) {
    bounds_.extend(c.p);
    rMax = std::max(rMax, std::fabs(c.radius));
  }
  bounds_.lo = bounds_.lo - Vec3(rMax);
  bounds_.hi = bounds_.hi + Vec3(rMax);
}

const char* Curves::embreeOnly() const {
  return "curves are intersected by Embree's own curve primitives; the in-house BVH has no "
         "curve intersector (use --accel embree)";
}

void Curves::evaluate(uint32_t segment, float u, Vec3& p, Vec3& dpdu, float& radius) const {
  const CurvePoint* c = &points_[segments_[segment]];
  float w[4], d[4];
  const float s = 1 - u;
  if (basis_ == CurveBasis::kBezier) {
    // Bernstein polynomials and their derivatives.
    w[0] = s * s * s, w[1] = 3 * u * s * s, w[2] = 3 * u * u * s, w[3] = u * u * u;
    d[0] = -3 * s * s, d[1] = 3 * s * s - 6 * u * s, d[2] = 6 * u * s - 3 * u * u, d[3] = 3 * u * u;
  } else {
    // Uniform cubic B-spline basis (Embree's, e.g. Foley et al. 11.2.3).
    w[0] = s * s * s / 6, w[1] = (3 * u * u * u - 6 * u * u + 4) / 6,
    w[2] = (-3 * u * u * u + 3 * u * u + 3 * u + 1) / 6, w[3] = u * u * u / 6;
    d[0] = -s * s / 2, d[1] = (3 * u * u - 4 * u) / 2, d[2] = (-3 * u * u + 2 * u + 1) / 2,
    d[3] = u * u / 2;
  }
  p = dpdu = Vec3(0.0f);
  radius = 0;
  for (int k = 0; k < 4; ++k) {
    p += w[k] * c[k].p;
    dpdu += d[k] * c[k].p;
    radius += w[k] * c[k].radius;
  }
}

bool Curves::shade(const Ray& local, const Hit& hit, ShapeShading& out) const {
  if (hit.triangle >= segments_.size()) return false;
  Vec3 p, dpdu;
  float radius;
  evaluate(hit.triangle, std::clamp(hit.uv.x, 0.0f, 1.0f), p, dpdu, radius);
  out.tangent = dpdu;
  if (shape_ == CurveShape::kRound) {
    out.ng = out.n = hit.normal;  // Embree's tube normal
    return true;
  }
  // A ribbon faces the ray (its geometric normal is -d made perpendicular to the tangent). Its
  // shading normal is the round fibre's at offset h = v across it (pbrt-v4 6.7's cylinder
  // curves; the hair BSDF reads h back from it, materials/hair_bsdf.h).
  const float tl = length(dpdu);
  if (!(tl > 0)) return false;
  const Vec3 t = dpdu / tl;
  Vec3 z = -(local.d - dot(local.d, t) * t);
  const float zl = length(z);
  if (!(zl > 0)) return false;
  z = z / zl;
  const Vec3 y = cross(z, t);
  const float h = std::clamp(hit.uv.y, -1.0f, 1.0f);
  out.ng = z;
  out.n = h * y + std::sqrt(std::max(0.0f, 1 - h * h)) * z;
  return true;
}

std::vector<uint32_t> curveSegmentsOfStrands(CurveBasis basis, const std::vector<uint32_t>& counts,
                                             size_t* badStrand) {
  std::vector<uint32_t> segments;
  uint32_t first = 0;
  for (size_t s = 0; s < counts.size(); ++s) {
    const uint32_t n = counts[s];
    const bool fits = basis == CurveBasis::kBSpline ? n >= 4 : n >= 4 && (n - 1) % 3 == 0;
    if (!fits) {
      if (badStrand) *badStrand = s;
      return {};
    }
    if (basis == CurveBasis::kBSpline)
      for (uint32_t k = 0; k + 3 < n; ++k) segments.push_back(first + k);
    else
      for (uint32_t k = 0; k + 3 < n; k += 3) segments.push_back(first + k);
    first += n;
  }
  return segments;
}

}  // namespace tray

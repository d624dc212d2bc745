// Sampling an emissive triangle by area, its pdf converted to solid angle at the receiver,
// written once over the lane type (core/lane_ops.h, docs/lanes.md). Scalar code includes
// lights/area_light.h (AreaLight::sampleTriangle); the SIMD stages include this file again in
// each target's pass and feed it rows of their emitter table.
#ifdef TRAY_LANES_SIMD
#if defined(LIGHTS_TRIANGLE_LIGHT_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef LIGHTS_TRIANGLE_LIGHT_LANES_H_SIMD_
#undef LIGHTS_TRIANGLE_LIGHT_LANES_H_SIMD_
#else
#define LIGHTS_TRIANGLE_LIGHT_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(LIGHTS_TRIANGLE_LIGHT_LANES_H_SCALAR_)
#define LIGHTS_TRIANGLE_LIGHT_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// An emissive triangle as sampling reads it: vertex 0, the edges to vertices 1 and 2, the unit
/// front normal, the area and whether both faces emit.
template <class V3>
struct TriangleLightOf {
  V3 p0, e1, e2, n;
  decltype(V3::x) area;
  MaskOf<decltype(V3::x)> doubleSided;
};

/// Solid-angle pdf of a triangle point at squared distance dist2 whose normal makes cosine
/// cosL with the direction: area pdf 1/A times dA/dw = d^2 / |cos|.
template <class F>
TRAY_LANE F triangleSolidAnglePdf(F dist2, F cosL, F area) {
  const F c = absOf(cosL);
  return select(c > F(0.0f), dist2 / (c * area), F(0.0f));
}

/// A point on the triangle for the receiver at `ref`: the point, the unit direction to it and
/// the solid-angle pdf. Valid (per lane) where the receiver is off the point and the light
/// faces it (one-sided lights emit from the front only).
template <class V3>
struct TriangleLightSampleOf {
  V3 p, wi;
  decltype(V3::x) pdf;
  MaskOf<decltype(V3::x)> valid;
};
template <class V3, class V2>
TRAY_LANE TriangleLightSampleOf<V3> sampleTriangleLight(const TriangleLightOf<V3>& t, const V3& ref,
                                                        const V2& u) {
  using F = decltype(V3::x);
  TriangleLightSampleOf<V3> s;
  const V3 b = sampleUniformTriangle(u);
  s.p = t.p0 + b.y * t.e1 + b.z * t.e2;
  const V3 d = s.p - ref;
  const F dist2 = lengthSquared(d);
  s.wi = d / sqrtOf(dist2);
  // Whether the light faces the receiver, on the cosine the pdf needs anyway: dot(n, -wi) and
  // -dot(n, wi) are equal but for the sign of a zero, which neither test sees.
  const F cosL = -dot(t.n, s.wi);
  s.pdf = triangleSolidAnglePdf(dist2, cosL, t.area);
  s.valid = dist2 > F(0.0f) && (t.doubleSided || cosL > F(0.0f));
  return s;
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

// Sampling an emissive triangle from a receiver, written once over the lane type
// (core/lane_ops.h, docs/lanes.md): uniformly by area, its pdf converted to solid angle, or
// uniformly in the solid angle it subtends (core/spherical_triangle_lanes.h), chosen per
// receiver by lights/triangle_sampling.h's rule. Scalar code includes lights/area_light.h
// (AreaLight::sampleTriangle, AreaLight::pdf); the SIMD stages include this file again in
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
#include "core/spherical_triangle_lanes.h"
#include "lights/triangle_sampling.h"

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

/// Where the triangle is sampled by solid angle from this receiver (TriangleSampling): a
/// function of the mode and the solid angle alone, so that sample and pdf agree.
template <class F>
TRAY_LANE MaskOf<F> bySolidAngle(TriangleSampling mode, F solidAngle) {
  const MaskOf<F> above = mode == TriangleSampling::kAuto ? solidAngle >= F(kMinSphericalSolidAngle)
                                                          : solidAngle > F(0.0f);
  return above && solidAngle <= F(kMaxSphericalSolidAngle);
}

/// Where kAuto surely samples the triangle by area, without its solid angle: the receiver is
/// outside the ball about the centroid through the farthest vertex (radius^2 r2, centre at
/// squared distance d2), so the triangle lies inside that ball's cone, whose solid angle is
/// 2 pi (1 - sqrt(1 - x)) <= 2 pi x / (2 - x) for x = r2 / d2 (1 - sqrt(1 - x) =
/// x / (1 + sqrt(1 - x)) and sqrt(1 - x) >= 1 - x). The bound is held to half of
/// kMinSphericalSolidAngle, so that the float solid angle that sphericalTriangleOf computes is
/// below the threshold too wherever the test holds (its relative error is far below 2:
/// tests/lights/triangle_sampling_test.cpp, ChoiceBoundIsConservative): the choice is the one
/// bySolidAngle makes, at 4 dot products instead of three normalisations, a triple product and
/// an atan2 (issue 37: `auto` cost 4-6% per sample where it computed the solid angle for
/// every sample).
template <class V3>
TRAY_LANE MaskOf<decltype(V3::x)> surelyByArea(const TriangleLightOf<V3>& t, const V3& ref) {
  using F = decltype(V3::x);
  const F third(1.0f / 3.0f);
  const V3 s = t.e1 + t.e2;
  const V3 c = t.p0 + third * s - ref;
  // From the centroid to the vertices: -(e1 + e2)/3, (2 e1 - e2)/3, (2 e2 - e1)/3.
  const V3 v1 = t.e1 + t.e1 - t.e2, v2 = t.e2 + t.e2 - t.e1;
  const F r2 =
      maxOf(lengthSquared(s), maxOf(lengthSquared(v1), lengthSquared(v2))) * F(1.0f / 9.0f);
  const F d2 = lengthSquared(c);
  return d2 > r2 && F(2.0f * kPi) * r2 < F(0.5f * kMinSphericalSolidAngle) * (F(2.0f) * d2 - r2);
}

/// The triangle seen from ref (its solid angle), for the modes that need it.
template <class V3>
TRAY_LANE SphericalTriangleOf<V3> sphericalTriangleFrom(const TriangleLightOf<V3>& t,
                                                        const V3& ref) {
  const V3 a = t.p0 - ref;
  return sphericalTriangleOf(a, a + t.e1, a + t.e2);
}

/// The receiver's cosine, folded into solid-angle sampling as pbrt-v4's Triangle::Sample does:
/// the square of u is warped bilinearly by |cos| between the receiver's shading normal n and
/// the directions to the vertices its corners map to (u.y = 0: b; (0, 1): a; (1, 1): c), at
/// least 0.01 (a vertex below the horizon may still have visible points beside it). A zero n
/// gives equal weights: no warp.
template <class V3>
TRAY_LANE BilinearOf<decltype(V3::x)> cosineWarpOf(const SphericalTriangleOf<V3>& s, const V3& n) {
  using F = decltype(V3::x);
  const F wb = maxOf(F(0.01f), absOf(dot(n, s.b)));
  return {wb, wb, maxOf(F(0.01f), absOf(dot(n, s.a))), maxOf(F(0.01f), absOf(dot(n, s.c)))};
}

/// Barycentrics (b1, b2) of where the ray from o along w meets the triangle's plane
/// (Moeller & Trumbore 1997), kept inside the triangle: a direction Arvo's construction put
/// on an edge may round to just outside it. (1/3, 1/3) where the ray is parallel.
template <class V3>
TRAY_LANE Vec2Of<decltype(V3::x)> barycentricsAlong(const TriangleLightOf<V3>& t, const V3& o,
                                                    const V3& w) {
  using F = decltype(V3::x);
  const V3 s1 = cross(w, t.e2);
  const F inv = F(1.0f) / dot(s1, t.e1);
  const V3 s = o - t.p0;
  F b1 = maxOf(dot(s, s1) * inv, F(0.0f)), b2 = maxOf(dot(w, cross(s, t.e1)) * inv, F(0.0f));
  const F sum = b1 + b2;
  b1 = select(sum > F(1.0f), b1 / sum, b1), b2 = select(sum > F(1.0f), b2 / sum, b2);
  const auto ok = isFiniteOf(b1) && isFiniteOf(b2);
  return {select(ok, b1, F(1.0f / 3.0f)), select(ok, b2, F(1.0f / 3.0f))};
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
/// The sample at the point p = p0 + a e1 + b e2 of the emitter t (a triangle, or a rectangle:
/// lights/rectangle_light_lanes.h) seen from ref: the unit direction, the pdf (solidAnglePdf
/// where the spherical construction was taken, else the area pdf converted to solid angle) and
/// whether it counts.
template <class V3>
TRAY_LANE TriangleLightSampleOf<V3> emitterSampleAt(const TriangleLightOf<V3>& t, const V3& ref,
                                                    decltype(V3::x) a, decltype(V3::x) b,
                                                    MaskOf<decltype(V3::x)> spherical,
                                                    decltype(V3::x) solidAnglePdf) {
  using F = decltype(V3::x);
  TriangleLightSampleOf<V3> s;
  s.p = t.p0 + a * t.e1 + b * t.e2;
  const V3 d = s.p - ref;
  const F dist2 = lengthSquared(d);
  s.wi = d / sqrtOf(dist2);
  // Whether the light faces the receiver, on the cosine the pdf needs anyway: dot(n, -wi) and
  // -dot(n, wi) are equal but for the sign of a zero, which neither test sees.
  const F cosL = -dot(t.n, s.wi);
  s.pdf = select(spherical, solidAnglePdf, triangleSolidAnglePdf(dist2, cosL, t.area));
  s.valid = dist2 > F(0.0f) && (t.doubleSided || cosL > F(0.0f));
  return s;
}

template <class V3, class V2>
TRAY_LANE TriangleLightSampleOf<V3> sampleTriangleLight(const TriangleLightOf<V3>& t, const V3& ref,
                                                        const V3& n, const V2& u,
                                                        TriangleSampling mode) {
  using F = decltype(V3::x);
  const V3 b = sampleUniformTriangle(u);
  F b1 = b.y, b2 = b.z, solidAnglePdf(0.0f);
  MaskOf<F> spherical(false);
  // kAuto: lanes that surelyByArea leave out need no solid angle (the same choice).
  if (mode != TriangleSampling::kArea &&  // the same for every lane: a plain branch
      (mode != TriangleSampling::kAuto || !allOf(surelyByArea(t, ref)))) {
    const SphericalTriangleOf<V3> st = sphericalTriangleFrom(t, ref);
    spherical = bySolidAngle(mode, st.area);
    if (anyOf(spherical)) {
      const BilinearOf<F> warp = cosineWarpOf(st, n);
      const V2 uw = sampleBilinear(u, warp);
      const Vec2Of<F> bw = barycentricsAlong(t, ref, sampleSphericalTriangle(st, uw));
      b1 = select(spherical, bw.x, b1), b2 = select(spherical, bw.y, b2);
      solidAnglePdf = bilinearPdf(uw, warp) / st.area;
    }
  }
  return emitterSampleAt(t, ref, b1, b2, spherical, solidAnglePdf);
}

/// The solid-angle pdf with which sampleTriangleLight from ref (shading normal n) returns the
/// unit direction wi, which meets the triangle at squared distance dist2 with cosine cosL to
/// its normal.
template <class V3>
TRAY_LANE decltype(V3::x) triangleLightPdf(const TriangleLightOf<V3>& t, const V3& ref, const V3& n,
                                           const V3& wi, decltype(V3::x) dist2,
                                           decltype(V3::x) cosL, TriangleSampling mode) {
  using F = decltype(V3::x);
  const F byArea = triangleSolidAnglePdf(dist2, cosL, t.area);
  if (mode == TriangleSampling::kArea) return byArea;
  if (mode == TriangleSampling::kAuto && allOf(surelyByArea(t, ref))) return byArea;
  const SphericalTriangleOf<V3> st = sphericalTriangleFrom(t, ref);
  const MaskOf<F> spherical = bySolidAngle(mode, st.area);
  if (noneOf(spherical)) return byArea;
  const F warped = bilinearPdf(invertSphericalTriangleSample(st, wi), cosineWarpOf(st, n));
  return select(spherical, warped / st.area, byArea);
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

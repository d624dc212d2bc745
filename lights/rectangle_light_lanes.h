// Sampling an emissive rectangle (two triangles of a mesh that form one, lights/quad_lights.h)
// from a receiver, written once over the lane type (core/lane_ops.h, docs/lanes.md):
// uniformly by area, its pdf converted to solid angle, or uniformly in the solid angle it
// subtends (core/spherical_rectangle_lanes.h, Urena et al. 2013) with the receiver's cosine
// folded in by pbrt-v4's bilinear warp, chosen per receiver as triangles are
// (lights/triangle_light_lanes.h, lights/triangle_sampling.h). Scalar code includes
// lights/area_light.h (AreaLight::sample, AreaLight::pdf).
#ifdef TRAY_LANES_SIMD
#if defined(LIGHTS_RECTANGLE_LIGHT_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef LIGHTS_RECTANGLE_LIGHT_LANES_H_SIMD_
#undef LIGHTS_RECTANGLE_LIGHT_LANES_H_SIMD_
#else
#define LIGHTS_RECTANGLE_LIGHT_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(LIGHTS_RECTANGLE_LIGHT_LANES_H_SCALAR_)
#define LIGHTS_RECTANGLE_LIGHT_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"
#include "core/spherical_rectangle_lanes.h"
#include "lights/triangle_light_lanes.h"
#include "lights/triangle_sampling.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

// A rectangle is a TriangleLightOf read differently: p0 a corner, e1 and e2 its perpendicular
// edges (the points p0 + s e1 + t e2 for s, t in [0, 1]), area |e1| |e2|.

/// Where the rectangle is sampled by solid angle from this receiver: triangles' rule
/// (bySolidAngle), but never below kMinSphericalRectangleSolidAngle, where its solid angle
/// is mostly float error.
template <class F>
TRAY_LANE MaskOf<F> rectangleBySolidAngle(TriangleSampling mode, F solidAngle) {
  const float lo =
      mode == TriangleSampling::kAuto ? kMinSphericalSolidAngle : kMinSphericalRectangleSolidAngle;
  return solidAngle >= F(lo) && solidAngle <= F(kMaxSphericalSolidAngle);
}

/// The rectangle's solid angle from the receiver where Urena et al.'s parametrization keeps
/// float precision, 0 (area sampling) elsewhere: at grazing elevations, z0^2 small against the
/// squared distance to the rectangle's points (at most 2 (|c|^2 + r^2), c its centre, r half
/// its diagonal), its 1 - cu^2 cancels, which matters where the solid angle is small too
/// (measured: a receiver 0.03 below a 2 x 0.8 panel's plane and 3 away, 1e-3 sr, had its
/// sample's pdf 0.8% off the inverse's; 0.05 below a 6 x 6 one, 6.19 sr, within 2e-3:
/// tests/lights/rectangle_sampling_test.cpp). Under sin^2 = 1e-3 (1.8 degrees) and 0.1 sr a
/// receiver sees a small light edge on, its cosine near 0: area sampling loses little.
template <class V3>
TRAY_LANE decltype(V3::x) preciseRectangleSolidAngle(const SphericalRectangleOf<V3>& r,
                                                     const TriangleLightOf<V3>& t, const V3& c) {
  using F = decltype(V3::x);
  const V3 diagonal = t.e1 + t.e2;
  const F far2 =
      F(2.0f) * (lengthSquared(c + F(0.5f) * diagonal) + F(0.25f) * lengthSquared(diagonal));
  return select(r.z0 * r.z0 >= F(1e-3f) * far2 || r.area >= F(0.1f), r.area, F(0.0f));
}

/// surelyByArea for a rectangle: the ball about its centre through its corners.
template <class V3>
TRAY_LANE MaskOf<decltype(V3::x)> surelyRectangleByArea(const TriangleLightOf<V3>& t,
                                                        const V3& ref) {
  using F = decltype(V3::x);
  const V3 diagonal = t.e1 + t.e2;
  const V3 c = t.p0 + F(0.5f) * diagonal - ref;
  const F r2 = F(0.25f) * lengthSquared(diagonal), d2 = lengthSquared(c);
  return d2 > r2 && F(2.0f * kPi) * r2 < F(0.5f * kMinSphericalSolidAngle) * (F(2.0f) * d2 - r2);
}

/// The receiver's cosine folded in as for triangles (cosineWarpOf): u's square warped
/// bilinearly by |cos| toward the corners u maps to, (0, 0) at p0, (1, 0) at p0 + e1, (0, 1)
/// at p0 + e2 (s: p0 from the receiver), at least 0.01; a zero n gives no warp.
template <class V3>
TRAY_LANE BilinearOf<decltype(V3::x)> rectangleCosineWarpOf(const V3& s, const V3& e1, const V3& e2,
                                                            const V3& n) {
  using F = decltype(V3::x);
  const auto w = [&](const V3& v) { return maxOf(F(0.01f), absOf(dot(n, normalize(v)))); };
  return {w(s), w(s + e1), w(s + e2), w(s + e1 + e2)};
}

/// A point on the rectangle for the receiver at `ref` with shading normal n, as
/// sampleTriangleLight gives one for a triangle.
template <class V3, class V2>
TRAY_LANE TriangleLightSampleOf<V3> sampleRectangleLight(const TriangleLightOf<V3>& t,
                                                         const V3& ref, const V3& n, const V2& u,
                                                         TriangleSampling mode) {
  using F = decltype(V3::x);
  F a = u.x, b = u.y, solidAnglePdf(0.0f);
  MaskOf<F> spherical(false);
  if (mode != TriangleSampling::kArea &&  // the same for every lane: a plain branch
      (mode != TriangleSampling::kAuto || !allOf(surelyRectangleByArea(t, ref)))) {
    const V3 c = t.p0 - ref;
    const SphericalRectangleOf<V3> r = sphericalRectangleOf(c, t.e1, t.e2);
    spherical = rectangleBySolidAngle(mode, preciseRectangleSolidAngle(r, t, c));
    if (anyOf(spherical)) {
      const BilinearOf<F> warp = rectangleCosineWarpOf(c, t.e1, t.e2, n);
      const V2 uw = sampleBilinear(u, warp);
      const Vec2Of<F> q = sampleSphericalRectangle(r, uw);
      // Back to the rectangle's own parameters, so that the point lies on it as an area
      // sample's does (the shadow ray ends on the emitter).
      const F one(1.0f), zero(0.0f);
      a = select(spherical, clampOf((q.x - r.x0) / r.exl, zero, one), a);
      b = select(spherical, clampOf((q.y - r.y0) / r.eyl, zero, one), b);
      solidAnglePdf = bilinearPdf(uw, warp) / r.area;
    }
  }
  return emitterSampleAt(t, ref, a, b, spherical, solidAnglePdf);
}

/// The solid-angle pdf with which sampleRectangleLight from ref (shading normal n) returns the
/// point ref + d of the rectangle (squared distance dist2, cosine cosL to its normal).
template <class V3>
TRAY_LANE decltype(V3::x) rectangleLightPdf(const TriangleLightOf<V3>& t, const V3& ref,
                                            const V3& n, const V3& d, decltype(V3::x) dist2,
                                            decltype(V3::x) cosL, TriangleSampling mode) {
  using F = decltype(V3::x);
  const F byArea = triangleSolidAnglePdf(dist2, cosL, t.area);
  if (mode == TriangleSampling::kArea) return byArea;
  if (mode == TriangleSampling::kAuto && allOf(surelyRectangleByArea(t, ref))) return byArea;
  const V3 c = t.p0 - ref;
  const SphericalRectangleOf<V3> r = sphericalRectangleOf(c, t.e1, t.e2);
  const MaskOf<F> spherical = rectangleBySolidAngle(mode, preciseRectangleSolidAngle(r, t, c));
  if (noneOf(spherical)) return byArea;
  const F warped =
      bilinearPdf(invertSphericalRectangleSample(r, d), rectangleCosineWarpOf(c, t.e1, t.e2, n));
  return select(spherical, warped / r.area, byArea);
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

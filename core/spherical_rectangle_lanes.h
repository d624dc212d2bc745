// Uniform sampling of the solid angle a rectangle subtends from a point, written once over the
// lane type (core/lane_ops.h, docs/lanes.md): C. Urena, M. Fajardo, A. King 2013, "An
// Area-Preserving Parametrization for Spherical Rectangles" (EGSR, Computer Graphics Forum
// 32(4)), section 3 and Algorithm 1 (pbrt-v4 A.5.6 has the same steps), and its inverse for
// the pdf of a direction that BSDF sampling found. lights/rectangle_light_lanes.h calls them
// for emissive rectangles (triangle pairs of a mesh, lights/quad_lights.h).
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_SPHERICAL_RECTANGLE_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_SPHERICAL_RECTANGLE_LANES_SIMD_
#undef TRAY_CORE_SPHERICAL_RECTANGLE_LANES_SIMD_
#else
#define TRAY_CORE_SPHERICAL_RECTANGLE_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_SPHERICAL_RECTANGLE_LANES_SCALAR_)
#define TRAY_CORE_SPHERICAL_RECTANGLE_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// A rectangle as seen from a point, in Urena et al.'s local frame (section 3.1): x and y along
/// its edges, z across it pointing away from the rectangle's side of the point (z0 <= 0), the
/// rectangle [x0, x1] x [y0, y1] at height z0; the unit edge-plane normals n0 and n2 of the
/// edges y = y0 and y = y1, b0 = n0.z, b1 = n2.z, and the solid angle `area` (steradians).
/// Urena et al. write the corner angles g0..g3 of the spherical quad, area = g0 + g1 + g2 +
/// g3 - 2 pi and k = 2 pi - g2 - g3; in float that sum near 2 pi loses about 1e-6 sr, 0.2% of a
/// 5e-4 sr rectangle (a pdf 0.8% off its inverse's, measured). Here each angle is kept as its
/// excess over a right angle, e_i = g_i - pi/2 = atan2(-cos g_i, sin g_i), small where the
/// quad is nearly planar: area = e0 + e1 + e2 + e3 and k = -(e2 + e3), so that Urena's
/// au = u area + (2 pi - g2 - g3) = pi + (u area + k).
template <class V3>
struct SphericalRectangleOf {
  using F = decltype(V3::x);
  V3 x, y, z, n0, n2;
  F x0, y0, x1, y1, z0, exl, eyl, b0, b1, k, area;
};

/// The angle between unit vectors a and b less pi/2, in [-pi/2, pi/2]: atan2 of minus the
/// cosine and the sine, precise near 0 (nearly perpendicular) where the angle's sum is not.
template <class V3>
TRAY_LANE decltype(V3::x) excessOverRightAngle(const V3& a, const V3& b) {
  return atan2Of(-dot(a, b), length(cross(a, b)));
}

/// The rectangle with corner s (relative to the point) and perpendicular edges ex, ey.
template <class V3>
TRAY_LANE SphericalRectangleOf<V3> sphericalRectangleOf(const V3& s, const V3& ex, const V3& ey) {
  using F = decltype(V3::x);
  SphericalRectangleOf<V3> r;
  r.exl = length(ex), r.eyl = length(ey);
  r.x = ex / r.exl, r.y = ey / r.eyl;
  const V3 z = cross(r.x, r.y);
  const F z0 = dot(s, z);
  r.z = select(z0 > F(0.0f), -z, z);
  r.z0 = -absOf(z0);
  r.x0 = dot(s, r.x), r.y0 = dot(s, r.y);
  r.x1 = r.x0 + r.exl, r.y1 = r.y0 + r.eyl;
  // The edge planes' normals, cross products of the corner directions (section 3.1), in the
  // local frame: n0 ~ (0, z0, -y0), n1 ~ (-z0, 0, x1), n2 ~ (0, -z0, y1), n3 ~ (z0, 0, -x0).
  const F zero(0.0f);
  r.n0 = normalize(V3{zero, r.z0, -r.y0});
  const V3 n1 = normalize(V3{-r.z0, zero, r.x1});
  r.n2 = normalize(V3{zero, -r.z0, r.y1});
  const V3 n3 = normalize(V3{r.z0, zero, -r.x0});
  const F e0 = excessOverRightAngle(-r.n0, n1), e1 = excessOverRightAngle(-n1, r.n2);
  const F e2 = excessOverRightAngle(-r.n2, n3), e3 = excessOverRightAngle(-n3, r.n0);
  r.b0 = r.n0.z, r.b1 = r.n2.z;
  r.k = -(e2 + e3);
  r.area = (e0 + e1) + (e2 + e3);
  return r;
}

/// A point uniform in the rectangle's solid angle (pdf 1 / r.area) for u in [0,1)^2, as its
/// local coordinates (xu, yv) (the point is xu x + yv y + z0 z from the receiver): Urena et
/// al.'s Algorithm 1. u.x chooses the solid angle u.x area of the sub-rectangle [x0, xu] x
/// [y0, y1], so the angle au = pi + u.x area + k of the spherical quad's corner; u.y is uniform in
/// the sine h of the elevation along x = xu. u = (0, 0) maps to the corner s, (1, 0) to
/// s + ex, (0, 1) to s + ey.
template <class V3, class V2>
TRAY_LANE Vec2Of<decltype(V3::x)> sampleSphericalRectangle(const SphericalRectangleOf<V3>& r,
                                                           const V2& u) {
  using F = decltype(V3::x);
  // au = pi + t, t = u.x area + k in (-pi, pi): cos au = -cos t, sin au = -sin t, so Urena's
  // fu = (cos(au) b0 - b1) / sin(au) = (cos(t) b0 + b1) / sin(t). cosSinTwoPi's polynomial
  // (the same in every lane) takes t / 2 pi in (-1/2, 1/2) as well.
  const Vec2Of<F> cs = cosSinTwoPi((u.x * r.area + r.k) * F(0.5f / kPi));
  const F fu = (cs.x * r.b0 + r.b1) / cs.y;
  F cu = copySignOf(F(1.0f) / sqrtOf(fu * fu + r.b0 * r.b0), fu);
  cu = clampOf(cu, F(-0x1.fffffep-1f), F(0x1.fffffep-1f));  // no NaN below
  const F xu = clampOf(-(cu * r.z0) / sqrtOf(F(1.0f) - cu * cu), r.x0, r.x1);
  const F d2 = xu * xu + r.z0 * r.z0, d = sqrtOf(d2);
  const F h0 = r.y0 / sqrtOf(d2 + r.y0 * r.y0), h1 = r.y1 / sqrtOf(d2 + r.y1 * r.y1);
  const F hv = h0 + u.y * (h1 - h0), hv2 = hv * hv;
  const F yv = select(hv2 < F(1.0f - 1e-6f), hv * d / sqrtOf(F(1.0f) - hv2), r.y1);
  return {xu, yv};
}

/// The u for which sampleSphericalRectangle(r, u) gives the point q (relative to the receiver,
/// on the rectangle): u.x the solid angle of the sub-rectangle [x0, xu] x [y0, y1] over the
/// whole's (its edge x = xu changes n1 alone, so e0 and e1 alone), u.y where the sine of q's
/// elevation lies between h0 and h1 (section 4's h). Clamped to [0,1]^2.
template <class V3>
TRAY_LANE Vec2Of<decltype(V3::x)> invertSphericalRectangleSample(const SphericalRectangleOf<V3>& r,
                                                                 const V3& q) {
  using F = decltype(V3::x);
  const F xu = clampOf(dot(q, r.x), r.x0, r.x1), yv = dot(q, r.y);
  const V3 n1 = normalize(V3{-r.z0, F(0.0f), xu});
  const F t = excessOverRightAngle(-r.n0, n1) + excessOverRightAngle(-n1, r.n2);  // au - pi
  const F d2 = xu * xu + r.z0 * r.z0;
  const F h0 = r.y0 / sqrtOf(d2 + r.y0 * r.y0), h1 = r.y1 / sqrtOf(d2 + r.y1 * r.y1);
  const F h = yv / sqrtOf(d2 + yv * yv);
  const F ux = (t - r.k) / r.area, uy = (h - h0) / (h1 - h0);
  return {clampOf(select(isFiniteOf(ux), ux, F(0.0f)), F(0.0f), F(1.0f)),
          clampOf(select(isFiniteOf(uy), uy, F(0.0f)), F(0.0f), F(1.0f))};
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

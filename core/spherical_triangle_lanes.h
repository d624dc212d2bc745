// Uniform sampling of the solid angle a triangle subtends from a point, written once over the
// lane type (core/lane_ops.h, docs/lanes.md): the spherical triangle's area by Van Oosterom &
// Strackee's formula, and Arvo's construction of a uniform direction inside it (J. Arvo 1995,
// "Stratified Sampling of Spherical Triangles", SIGGRAPH; pbrt-v4 6.5.4 has the same steps).
// lights/triangle_light_lanes.h calls them for emissive triangles.
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_SPHERICAL_TRIANGLE_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_SPHERICAL_TRIANGLE_LANES_SIMD_
#undef TRAY_CORE_SPHERICAL_TRIANGLE_LANES_SIMD_
#else
#define TRAY_CORE_SPHERICAL_TRIANGLE_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_SPHERICAL_TRIANGLE_LANES_SCALAR_)
#define TRAY_CORE_SPHERICAL_TRIANGLE_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// A triangle as seen from a point: the unit directions a, b, c to its vertices and the solid
/// angle it subtends (steradians; NaN where the point is on a vertex).
template <class V3>
struct SphericalTriangleOf {
  V3 a, b, c;
  decltype(V3::x) area;
};

/// The triangle whose vertices lie at pa, pb, pc relative to the point. Area: Van Oosterom &
/// Strackee 1983 ("The Solid Angle of a Plane Triangle", IEEE Trans. Biomed. Eng. 30(2)),
/// tan(omega / 2) = |a.(b x c)| / (1 + a.b + b.c + c.a) for unit a, b, c: no cancellation
/// for small triangles, unlike Girard's alpha + beta + gamma - pi, and atan2 carries the
/// omega > pi side (a negative denominator).
template <class V3>
TRAY_LANE SphericalTriangleOf<V3> sphericalTriangleOf(const V3& pa, const V3& pb, const V3& pc) {
  using F = decltype(V3::x);
  SphericalTriangleOf<V3> s;
  s.a = normalize(pa), s.b = normalize(pb), s.c = normalize(pc);
  const F num = absOf(dot(s.a, cross(s.b, s.c)));
  const F den = F(1.0f) + dot(s.a, s.b) + dot(s.b, s.c) + dot(s.c, s.a);
  s.area = F(2.0f) * atan2Of(num, den);
  return s;
}

/// A unit direction uniform in the spherical triangle s (pdf 1 / s.area) for u in [0,1)^2:
/// u.x chooses the area A' = u.x s.area of the sub-triangle a b c' (c' on the arc a c), u.y
/// the point on the arc b c' (Arvo 1995, section 2, "Algorithm"). Defined where s.area is
/// well inside (0, 2 pi) (lights/triangle_sampling.h's bounds); a degenerate lane gives
/// finite garbage or NaN, which its caller discards.
template <class V3, class V2>
TRAY_LANE V3 sampleSphericalTriangle(const SphericalTriangleOf<V3>& s, const V2& u) {
  using F = decltype(V3::x);
  const V3 &a = s.a, &b = s.b, &c = s.c;
  // The angle alpha at vertex a, between the great circles through a b and through a c.
  const V3 nab = normalize(cross(a, b)), nca = normalize(cross(c, a));
  const F cosAlpha = -dot(nab, nca);
  const F sinAlpha = length(cross(nab, nca));
  // sin and cos of A' - alpha (Arvo's s and t), from A' = 2 pi (u.x s.area / 2 pi).
  const Vec2Of<F> cs = cosSinTwoPi(u.x * s.area * F(0.5f / kPi));
  const F sinP = cs.y * cosAlpha - cs.x * sinAlpha;
  const F cosP = cs.x * cosAlpha + cs.y * sinAlpha;
  // Arvo's u, v and q = cos of the arc a c', the sub-triangle's third vertex.
  const F uu = cosP - cosAlpha;
  const F vv = sinP + sinAlpha * dot(a, b);
  const F q = ((vv * cosP - uu * sinP) * cosAlpha - vv) / ((vv * sinP + uu * cosP) * sinAlpha);
  const F cosAc = select(isFiniteOf(q), clampOf(q, F(-1.0f), F(1.0f)), F(1.0f));
  const F sinAc = sqrtOf(maxOf(F(1.0f) - cosAc * cosAc, F(0.0f)));
  const V3 cp = cosAc * a + sinAc * normalize(c - dot(c, a) * a);
  // Along the arc from b to c': z = cos of the arc to b, uniform in [b.c', 1].
  const F z = F(1.0f) - u.y * (F(1.0f) - dot(cp, b));
  const F sinZ = sqrtOf(maxOf(F(1.0f) - z * z, F(0.0f)));
  return z * b + sinZ * normalize(cp - dot(cp, b) * b);
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

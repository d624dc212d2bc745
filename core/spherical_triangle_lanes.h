// Uniform sampling of the solid angle a triangle subtends from a point, written once over the
// lane type (core/lane_ops.h, docs/lanes.md): the spherical triangle's area by Van Oosterom &
// Strackee's formula, and Arvo's construction of a uniform direction inside it (J. Arvo 1995,
// "Stratified Sampling of Spherical Triangles", SIGGRAPH; pbrt-v4 6.5.4 has the same steps),
// its sub-triangle found from Van Oosterom & Strackee's formula, which float keeps precise.
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

/// A unit direction uniform in the spherical triangle s (pdf 1 / s.area) for u in [0,1)^2,
/// by Arvo's two steps (1995, section 2): u.x chooses the area A' = u.x s.area of the
/// sub-triangle a b c' (c' on the arc from a to c), u.y the point on the arc from b to c'.
///
/// Arvo finds c' from the angle at a, through cos(A' - alpha) - cos(alpha): in float that
/// cancels for thin or small triangles (a receiver near the plane of a large emitter: 0.008
/// radians of error in the direction of a 0.03 sr sliver, where the sliver is 0.02 wide).
/// Here c' = cos(theta) a + sin(theta) c_perp solves Van Oosterom & Strackee's formula for the
/// sub-triangle instead: with k = a.b, m = |a.(b x c_perp)| and the half area A'/2,
///   sin(A'/2) (1 + k + (1 + k) cos(theta) + sin(theta) b.c_perp) = cos(A'/2) sin(theta) m,
/// which with the half-angle identities gives tan(theta/2) = y / x, y = sin(A'/2) (1 + k),
/// x = cos(A'/2) m - sin(A'/2) b.c_perp; cos and sin of theta follow from x and y without trig.
/// Along the arc, Arvo's z = cos(arc to b) is uniform in [b.c', 1]: 1 - z = u.y |c' - b|^2 / 2,
/// exact for unit vectors, where 1 - b.c' would cancel. Float errors: at most 4e-7 in the
/// direction for those triangles (1e-5 near a hemisphere), against 1e-2 with Arvo's formula.
/// Defined where s.area is in (0, 2 pi) (lights/triangle_sampling.h's bounds); a degenerate
/// lane gives NaN or garbage, which its caller discards.
template <class V3, class V2>
TRAY_LANE V3 sampleSphericalTriangle(const SphericalTriangleOf<V3>& s, const V2& u) {
  using F = decltype(V3::x);
  const V3 &a = s.a, &b = s.b, &c = s.c;
  const V3 ac = c - a;  // c's part across a, from the small difference: no cancellation
  const V3 cPerp = normalize(ac - dot(ac, a) * a);
  const F m = absOf(dot(a, cross(b, cPerp)));
  const Vec2Of<F> half = cosSinTwoPi(u.x * s.area * F(0.25f / kPi));  // (cos, sin) of A'/2
  const F y = half.y * (F(1.0f) + dot(a, b));
  const F x = half.x * m - half.y * dot(b, cPerp);
  const F r2 = x * x + y * y;
  const V3 cp = ((x * x - y * y) / r2) * a + ((F(2.0f) * x * y) / r2) * cPerp;
  const V3 d = cp - b;
  const F oneMinusZ = u.y * (dot(d, d) * F(0.5f));
  const F sinZ = sqrtOf(oneMinusZ * (F(2.0f) - oneMinusZ));
  return (F(1.0f) - oneMinusZ) * b + sinZ * normalize(d - dot(d, b) * b);
}

/// The u for which sampleSphericalTriangle(s, u) gives the unit direction w inside s: c' is
/// where the great circle through b and w meets the arc from a to c, u.x the area of a b c'
/// over s.area, u.y = |w - b|^2 / |c' - b|^2 (the forward map's 1 - z over 1 - b.c').
/// Clamped to [0,1]^2; near b, where c' is ill-defined, u.x is too and u.y ~ 0.
template <class V3>
TRAY_LANE Vec2Of<decltype(V3::x)> invertSphericalTriangleSample(const SphericalTriangleOf<V3>& s,
                                                                const V3& w) {
  using F = decltype(V3::x);
  V3 cp = normalize(cross(cross(s.b, w), cross(s.a, s.c)));
  cp = select(dot(cp, s.a + s.c) < F(0.0f), -cp, cp);
  const F area = sphericalTriangleOf(s.a, s.b, cp).area;
  const F ux = select(isFiniteOf(area), area / s.area, F(0.0f));
  const V3 dw = w - s.b, dc = cp - s.b;
  const F uy = dot(dw, dw) / dot(dc, dc);
  return {clampOf(ux, F(0.0f), F(1.0f)), clampOf(uy, F(0.0f), F(1.0f))};
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

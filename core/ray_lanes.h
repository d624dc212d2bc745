// Where a ray leaving a surface starts, written once over the lane type (core/lane_ops.h,
// docs/lanes.md): the point pushed off the surface along the geometric normal, on the side
// the ray goes. Scalar code includes core/ray.h; a SIMD stage includes this file again in
// each target's pass with TRAY_LANES_SIMD defined.
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_RAY_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_RAY_LANES_SIMD_
#undef TRAY_CORE_RAY_LANES_SIMD_
#else
#define TRAY_CORE_RAY_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_RAY_LANES_SCALAR_)
#define TRAY_CORE_RAY_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// One coordinate p of a surface point moved off the surface along n's coordinate: a few ULPs
/// (256 n integer steps of p's float) away from 0, a fixed 2^-16 n near 0, where ULPs vanish
/// (Wächter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing
/// Gems ch. 6). Selects, not branches: the signs of p and n are random from one bounce to the
/// next, so branches on them are mispredicted half the time.
template <class F>
TRAY_LANE F offsetCoordinate(F p, F n) {
  using I = IntOf<F>;
  const I offset = truncateToInt(F(256.0f) * n);
  const I moved = bitsOf(p) + select(p < F(0.0f), -offset, offset);
  return select(absOf(p) < F(1.0f / 32.0f), p + F(1.0f / 65536.0f) * n, floatFromBits(moved));
}
/// A surface point moved off the surface along n (offsetCoordinate per axis).
template <class V3>
TRAY_LANE V3 offsetRayOrigin(const V3& p, const V3& n) {
  return {offsetCoordinate(p.x, n.x), offsetCoordinate(p.y, n.y), offsetCoordinate(p.z, n.z)};
}
/// The origin of a ray from p (geometric normal ng) going `toward` (a direction, or a target
/// minus p): offset to the side of ng the ray goes. ng's sign flip is exact.
template <class V3>
TRAY_LANE V3 spawnOrigin(const V3& p, const V3& ng, const V3& toward) {
  using F = decltype(V3::x);
  return offsetRayOrigin(p, ng * select(dot(toward, ng) >= F(0.0f), F(1.0f), F(-1.0f)));
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

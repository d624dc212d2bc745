// An affine transform applied to points, vectors and normals, written once over the lane type
// (core/lane_ops.h, docs/lanes.md): Transform::point, vector and normal (core/transform.h) call
// these with Vec3; the SIMD kernels (integrators/surface_batch.cpp, camera_batch.cpp) include
// this file again in each target's pass with TRAY_LANES_SIMD defined. The matrices are Mat4's
// raw rows (float[4][4]): a type of namespace tray would bring tray's scalar templates into a
// SIMD call by argument-dependent lookup, beside the target's own.
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_TRANSFORM_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_TRANSFORM_LANES_SIMD_
#undef TRAY_CORE_TRANSFORM_LANES_SIMD_
#else
#define TRAY_CORE_TRANSFORM_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_TRANSFORM_LANES_SCALAR_)
#define TRAY_CORE_TRANSFORM_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// The first three rows of the row-major matrix a times (p, w): w = 1 a point, w = 0 a vector
/// (its translation term a[r][3] * 0 is kept: it gives -0 its sign). Each row's terms left to
/// right.
template <class V3>
TRAY_LANE V3 applyAffine(const float (&a)[4][4], const V3& p, decltype(V3::x) w) {
  using F = decltype(V3::x);
  return {F(a[0][0]) * p.x + F(a[0][1]) * p.y + F(a[0][2]) * p.z + F(a[0][3]) * w,
          F(a[1][0]) * p.x + F(a[1][1]) * p.y + F(a[1][2]) * p.z + F(a[1][3]) * w,
          F(a[2][0]) * p.x + F(a[2][1]) * p.y + F(a[2][2]) * p.z + F(a[2][3]) * w};
}
/// A point p placed by the matrix m (Transform::point).
template <class V3>
TRAY_LANE V3 transformPoint(const float (&m)[4][4], const V3& p) {
  return applyAffine(m, p, 1.0f);
}
/// A vector v placed by the matrix m (Transform::vector).
template <class V3>
TRAY_LANE V3 transformVector(const float (&m)[4][4], const V3& v) {
  return applyAffine(m, v, 0.0f);
}
/// A normal placed by the matrix whose inverse is inv: by the inverse transpose, so that it
/// stays perpendicular under non-uniform scale (Transform::normal).
template <class V3>
TRAY_LANE V3 transformNormal(const float (&inv)[4][4], const V3& n) {
  using F = decltype(V3::x);
  return {F(inv[0][0]) * n.x + F(inv[1][0]) * n.y + F(inv[2][0]) * n.z,
          F(inv[0][1]) * n.x + F(inv[1][1]) * n.y + F(inv[2][1]) * n.z,
          F(inv[0][2]) * n.x + F(inv[1][2]) * n.y + F(inv[2][2]) * n.z};
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

// A pinhole perspective camera's rays, written once over the lane type (core/lane_ops.h,
// docs/lanes.md): Integrator::cameraRay's raster position and PerspectiveCamera::generateRay
// (core/camera.cpp) call these with float; the SIMD camera kernel integrators/camera_batch.cpp
// includes this file again in each target's pass with TRAY_LANES_SIMD defined.
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_CAMERA_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_CAMERA_LANES_SIMD_
#undef TRAY_CORE_CAMERA_LANES_SIMD_
#else
#define TRAY_CORE_CAMERA_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_CAMERA_LANES_SCALAR_)
#define TRAY_CORE_CAMERA_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/transform_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// A raster coordinate of pixel index `pixel` (x or y), `offset` from its centre.
template <class F>
TRAY_LANE F rasterCoordinate(F pixel, F offset) {
  return (pixel + F(0.5f)) + offset;
}

/// The camera-space direction through raster position (x, y) (x right, y down, in pixels) of a
/// perspective camera with an image of width x height pixels and tan(fov / 2) tanHalfX,
/// tanHalfY: ((2x/w - 1) tanHalfX, (1 - 2y/h) tanHalfY, -1).
template <class F>
TRAY_LANE Vec3Of<F> perspectiveDirection(F x, F y, float width, float height, float tanHalfX,
                                         float tanHalfY) {
  return {(F(2.0f) * x / F(width) - F(1.0f)) * F(tanHalfX),
          (F(1.0f) - F(2.0f) * y / F(height)) * F(tanHalfY), F(-1.0f)};
}

/// The world direction d and start tmin of the pinhole ray along camera-space dirCam (z = -1)
/// from a camera placed by the matrix m: the point at view depth znear is znear * dirCam.
template <class V3>
TRAY_LANE void pinholeRay(const float (&m)[4][4], const V3& dirCam, float znear, V3& d,
                          decltype(V3::x)& tmin) {
  using F = decltype(V3::x);
  const V3 w = transformVector(m, dirCam);
  d = normalize(w);
  tmin = F(znear) * length(w);
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

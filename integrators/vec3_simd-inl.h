// Vec3 arithmetic over SIMD lanes (x, y, z each a vector), shared by the SIMD kernels that
// repeat core/math.h's Vec3 operators bit for bit (integrators/surface_batch.cpp,
// integrators/matte_batch.cpp): each function is its scalar twin's operations in the same
// order, and the kernels build with -ffp-contract=off. Highway's -inl.h convention: included
// once per target after hwy/highway.h, guarded per target by HWY_TARGET_TOGGLE.
#if defined(TRAY_CORE_VEC3_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_VEC3_SIMD_INL_H_
#undef TRAY_CORE_VEC3_SIMD_INL_H_
#else
#define TRAY_CORE_VEC3_SIMD_INL_H_
#endif

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET != HWY_SCALAR  // the kernels' callers keep to scalar code without SIMD
/// A Vec3 per lane.
struct V3 {
  hn::Vec<hn::ScalableTag<float>> x, y, z;
};
using V3Lane = hn::Vec<hn::ScalableTag<float>>;

/// dot(a, b): (a.x b.x + a.y b.y) + a.z b.z.
HWY_INLINE V3Lane Dot(const V3& a, const V3& b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
/// a - b.
HWY_INLINE V3 Sub(const V3& a, const V3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
/// a * s.
HWY_INLINE V3 Scale(const V3& a, V3Lane s) {
  return {a.x * s, a.y * s, a.z * s};
}
#endif  // HWY_TARGET != HWY_SCALAR

}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#endif  // TRAY_CORE_VEC3_SIMD_INL_H_

// Opens the namespace a one-text header (*_lanes.h) defines its templates in; core/lanes_end.h
// closes it. Without TRAY_LANES_SIMD: namespace tray, for the scalar lane (F = float). With it
// (a SIMD stage's per-target pass, after hwy/highway.h and core/lane_simd-inl.h): the target's
// own namespace, under its target attributes, so the same templates compile for FloatVec
// there (docs/lanes.md). No include guard: each *_lanes.h body includes it once.
#ifdef TRAY_LANES_SIMD
HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
/// The one-text functions: inlined into the SIMD kernels (a vector per argument).
#define TRAY_LANE HWY_INLINE
#else
namespace tray {
#define TRAY_LANE inline
#endif

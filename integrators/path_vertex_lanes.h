// What one path vertex adds and carries on, written once over the lane type (core/lane_ops.h,
// docs/lanes.md): next-event estimation's contribution and the throughput after the BSDF
// sample. PathEstimator (integrators/path_estimator.cpp) calls these for one path; the SIMD
// stages (integrators/matte_batch.cpp, glossy_batch.cpp) for a vector of them.
#ifdef TRAY_LANES_SIMD
#if defined(INTEGRATORS_PATH_VERTEX_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef INTEGRATORS_PATH_VERTEX_LANES_H_SIMD_
#undef INTEGRATORS_PATH_VERTEX_LANES_H_SIMD_
#else
#define INTEGRATORS_PATH_VERTEX_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(INTEGRATORS_PATH_VERTEX_LANES_H_SCALAR_)
#define INTEGRATORS_PATH_VERTEX_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// A light sample's estimate through the vertex: beta f L w / pdf, with f the BSDF times the
/// cosine at the receiver, w the MIS weight and pdf the light sample's (choice x solid angle).
template <class V3, class F>
TRAY_LANE V3 neeContribution(const V3& beta, const V3& f, const V3& L, F w, F pdf) {
  return beta * f * L * (w / pdf);
}
/// The throughput after a BSDF sample (f, wi, pdf) at shading normal n: beta f |cos| / pdf.
template <class V3, class F>
TRAY_LANE V3 scatteredThroughput(const V3& beta, const V3& f, const V3& wi, const V3& n, F pdf) {
  return beta * (f * (absOf(dot(wi, n)) / pdf));
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

// Where a pixel's samples go (docs/anti-aliasing.md), written once over the lane type
// (core/lane_ops.h, docs/lanes.md): PixelSampler::offset (core/pixel_sampler.cpp) calls it with
// float; the SIMD camera kernel integrators/camera_batch.cpp includes this file again in each
// target's pass with TRAY_LANES_SIMD defined.
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_PIXEL_SAMPLER_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_PIXEL_SAMPLER_LANES_SIMD_
#undef TRAY_CORE_PIXEL_SAMPLER_LANES_SIMD_
#else
#define TRAY_CORE_PIXEL_SAMPLER_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_PIXEL_SAMPLER_LANES_SCALAR_)
#define TRAY_CORE_PIXEL_SAMPLER_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// PixelSampler::offset: the offset from the pixel centre of sample i < sampler.count(); u is
/// uniform in [0,1)^2 and is only used by jitter and sequence. P: PixelSampler (a template
/// parameter, so that this file needs no declaration of it). The pattern is the same for every
/// lane. A SIMD caller names this function with its namespace: PixelSampler's, tray, would
/// bring the scalar template in too (argument-dependent lookup).
template <class F, class P>
TRAY_LANE Vec2Of<F> pixelOffset(const P& sampler, IntOf<F> i, const Vec2Of<F>& u) {
  using I = IntOf<F>;
  using Pattern = typename P::Pattern;
  const F radius(sampler.radius());
  switch (sampler.pattern()) {
    case Pattern::kCenter:
      return {F(0.0f), F(0.0f)};
    case Pattern::kCorners:
      return {select((i & I(1)) == I(0), F(-0.5f), F(0.5f)),
              select((i & I(2)) == I(0), F(-0.5f), F(0.5f))};
    case Pattern::kSequence:
      return {(F(2.0f) * u.x - F(1.0f)) * radius, (F(2.0f) * u.y - F(1.0f)) * radius};
    case Pattern::kGrid:
    case Pattern::kJitter: {
      const int32_t n = sampler.strata();
      const bool grid = sampler.pattern() == Pattern::kGrid;
      // Jitter's samples past the n x n strata are uniform.
      const MaskOf<F> stratified = MaskOf<F>(grid) || i < I(n * n);
      Vec2Of<F> s = u;  // position in [0,1)^2 of the support
      if (anyOf(stratified)) {
        I q, r;  // i / n, i % n
        divModOf(i, n, q, r);
        const F dx = grid ? F(0.5f) : u.x, dy = grid ? F(0.5f) : u.y;
        s.x = select(stratified, (toFloatOf(r) + dx) / F(float(n)), u.x);
        s.y = select(stratified, (toFloatOf(q) + dy) / F(float(n)), u.y);
      }
      return {(F(2.0f) * s.x - F(1.0f)) * radius, (F(2.0f) * s.y - F(1.0f)) * radius};
    }
  }
  return {F(0.0f), F(0.0f)};
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

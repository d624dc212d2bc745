// Sampling a KHR_lights_punctual light (point, spot, directional), written once over the lane
// type (core/lane_ops.h, docs/lanes.md). Scalar code includes lights/punctual_light.h
// (PunctualLight::sample); the SIMD stages include this file again in each target's pass and
// feed it rows of their punctual table.
#ifdef TRAY_LANES_SIMD
#if defined(LIGHTS_PUNCTUAL_LIGHT_LANES_H_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef LIGHTS_PUNCTUAL_LIGHT_LANES_H_SIMD_
#undef LIGHTS_PUNCTUAL_LIGHT_LANES_H_SIMD_
#else
#define LIGHTS_PUNCTUAL_LIGHT_LANES_H_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(LIGHTS_PUNCTUAL_LIGHT_LANES_H_SCALAR_)
#define LIGHTS_PUNCTUAL_LIGHT_LANES_H_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/sampling_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// A punctual light as sampling reads it: what it is, where, which way its light travels (spot,
/// directional), its intensity (point, spot: radiant intensity; directional: irradiance) and a
/// spot's cone cosines.
template <class V3>
struct PunctualLightOf {
  using F = decltype(V3::x);
  MaskOf<F> directional, spot;
  V3 position, direction, intensity;
  F cosOuter, cosInner;
};

/// The light toward a receiver at p: a delta in direction (pdf 1, not a density). wi the unit
/// direction toward the light, L the radiance-like term the estimate multiplies (intensity /
/// d^2 times a spot's falloff; a directional light's irradiance). `valid` false where the
/// receiver is at the light or nothing reaches it (L black), as PunctualLight::sample.
template <class V3>
struct PunctualLightSampleOf {
  V3 wi, L;
  MaskOf<decltype(V3::x)> valid;
};

/// KHR_lights_punctual's spot attenuation at cos(angle to the axis) cd: linear in cos between
/// the cone angles, squared for a smooth edge (the extension's reference implementation).
template <class F>
TRAY_LANE F spotFalloffOf(F cd, F cosOuter, F cosInner) {
  const F t = clampOf((cd - cosOuter) / maxOf(cosInner - cosOuter, F(1e-4f)), F(0.0f), F(1.0f));
  return t * t;
}

template <class V3>
TRAY_LANE PunctualLightSampleOf<V3> samplePunctualLight(const PunctualLightOf<V3>& l,
                                                        const V3& p) {
  using F = decltype(V3::x);
  PunctualLightSampleOf<V3> s;
  s.wi = -l.direction;
  s.L = l.intensity;
  s.valid = l.directional;
  if (!allOf(l.directional)) {  // for one float: only a point or spot light
    const V3 d = l.position - p;
    const F dist2 = lengthSquared(d);
    const V3 wi = d / sqrtOf(dist2);
    F falloff(1.0f);
    if (anyOf(l.spot))
      falloff = select(l.spot, spotFalloffOf(dot(-wi, l.direction), l.cosOuter, l.cosInner),
                       falloff);
    const V3 L = l.intensity * (falloff / dist2);
    s.wi = select(l.directional, s.wi, wi);
    s.L = select(l.directional, s.L, L);
    s.valid = l.directional || (dist2 > F(0.0f) && !isBlack(L));
  }
  return s;
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

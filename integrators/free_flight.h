#pragma once
// Free-flight distance sampling in a homogeneous chromatic medium (docs/subsurface.md).
// A path draws its distances by one colour channel's extinction, the "hero" channel chosen
// uniformly once per path, and is weighted by the one-sample MIS (balance heuristic) over the
// three channels of the *whole path's* pdf: f(path) / ((1/3) sum_c p_c(path)), the hero
// wavelength sampling of Wilkie et al. 2014 as pbrt-v4 does it (Pharr et al. 2023, section
// 14.2.2, its rescaled path probabilities r_u). The ratios r_c = p_c / mean(p) carried along
// the path keep that weight at most 3 f_c / p_c in every channel; weighting each event alone
// (the pdfs' mean per event) would be unbiased too, but its weights are products of per-event
// ratios and blow up in long walks through media whose channels differ (measured: a furnace
// 19% dark in its densest channel at 40k samples).
#include <cmath>

#include "core/math.h"

namespace tray {

/// One free flight along a segment of length tMax (infinite: the ray left the scene).
struct FreeFlight {
  bool scattered = false;  ///< a medium event at distance t < tMax; else the flight reached tMax
  float t = 0;
  /// What the path throughput is multiplied by: f / p of the flight with p the channels' pdfs
  /// weighted by the path's ratios, sigma_s T(t) / mean(r sigma_t T(t)) at a medium event (the
  /// phase function is then sampled exactly, weight 1), T(tMax) / mean(r T(tMax)) otherwise.
  Color weight{0.0f};
};

/// exp(-sigma t) per channel, 1 where sigma is 0 (also for an infinite t).
inline Color extinctionTransmittance(const Color& sigmaT, float t) {
  auto one = [t](float s) { return s > 0 ? std::exp(-s * t) : 1.0f; };
  return {one(sigmaT.x), one(sigmaT.y), one(sigmaT.z)};
}

/// The hero channel of a path, from a uniform number in [0, 1).
inline int heroChannel(float u) {
  return std::min(int(u * 3.0f), 2);
}

/// Draws the flight by channel `hero`'s extinction with `u` uniform in [0, 1). `ratios`: the
/// path's pdf per channel over their mean so far (1, 1, 1 before its first flight), updated.
inline FreeFlight sampleFreeFlight(const Color& sigmaA, const Color& sigmaS, float tMax, int hero,
                                   float u, Color& ratios) {
  const Color sigmaT = sigmaA + sigmaS;
  FreeFlight f;
  // t = -ln(1 - u) / sigma_t[hero]: pdf sigma_t exp(-sigma_t t); a channel that does not
  // attenuate never stops the flight.
  const float sh = sigmaT[hero];
  const float t = sh > 0 ? -std::log1p(-u) / sh : kInfinity;
  f.scattered = t < tMax;
  f.t = f.scattered ? t : tMax;
  const Color T = extinctionTransmittance(sigmaT, f.t);
  // Each channel's pdf of this flight: of stopping at t, or of passing tMax.
  const Color p = f.scattered ? sigmaT * T : T;
  const Color rp = ratios * p;
  const float mean = (rp.x + rp.y + rp.z) / 3.0f;
  if (!(mean > 0)) return f;  // weight 0: a flight no channel could have drawn
  f.weight = (f.scattered ? sigmaS * T : T) / mean;
  ratios = rp / mean;
  return f;
}

}  // namespace tray

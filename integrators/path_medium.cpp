// The path tracer inside a homogeneous scattering medium (TRAY_materials_scattering,
// docs/subsurface.md): a random walk between the dielectric boundary's surfaces, as Cycles'
// and Arnold's random-walk subsurface scattering (and pbrt-v4's VolPathIntegrator without its
// light sampling in media, Pharr et al. 2023, section 14.2).
#include <algorithm>
#include <cmath>

#include "integrators/free_flight.h"
#include "integrators/path_estimator.h"
#include "materials/henyey_greenstein.h"

namespace tray {

bool PathEstimator::mediumEvent(PathState& st, Sampler& sampler, const Hit* hit, DrawsAhead& ahead,
                                RayStats& stats, PathStep& next) const {
  // The vertex's draws in step's order: those made ahead while they last (the wavefront's),
  // each skipping the sampler past it, then the sampler's own; what is left stays for the hit.
  const auto draw = [&]() -> Vec3 {
    if (!ahead.first) return sampler.next3D();
    sampler.skip3D();
    const Vec3 u = *ahead.first;
    ahead.first = ahead.second, ahead.second = nullptr;
    return u;
  };
  Color sigmaA, sigmaS;
  float g = 0;
  st.media.currentScattering(sigmaA, sigmaS, g);
  const float speed = length(st.ray.d);  // world distance per unit of the ray's t
  const float tMax = hit ? hit->t * speed : kInfinity;
  const Vec3 u = draw();  // the hero channel (the path's first flight only), the distance
  if (st.heroChannel < 0) st.heroChannel = int8_t(heroChannel(u.x));
  const FreeFlight flight =
      sampleFreeFlight(sigmaA, sigmaS, tMax, st.heroChannel, u.y, st.channelRatios);
  st.beta *= flight.weight;
  if (!flight.scattered) return false;
  next = PathStep::kDone;
  if (!throughputLives(st) || ++st.mediumEvents > kMaxMediumEvents) return true;
  // A medium event: the phase function sampled exactly (weight 1). No light is sampled here,
  // so whatever the next segment finds (through the smooth boundary, an emitter inside) counts
  // in full, as after a delta lobe.
  const Vec3 dIn = st.ray.d / speed;
  const Vec3 p = st.ray.o + dIn * flight.t;
  const Vec3 w = draw();  // (w.y, w.z): the direction
  float pdf;
  const Vec3 dOut = sampleHenyeyGreenstein(dIn, g, {w.y, w.z}, pdf);
  st.ray.o = p, st.ray.d = dOut;
  st.ray.tmin = 0.0f, st.ray.tmax = kInfinity;  // inside the medium: no surface to leave
  st.specular = true;
  st.indirectEmission = st.indirectNee;
  st.indirectNee = true;
  st.prevPdf = pdf;
  ++stats.secondaryRays;
  // Russian roulette as after a surface (roulette()), and after kRouletteMediumEvents events
  // too: a walk in a bright medium would otherwise run to kMaxMediumEvents.
  if ((st.depth > rouletteDepth_ || st.mediumEvents > kRouletteMediumEvents) &&
      !survivesRoulette(st, sampler))
    return true;
  next = PathStep::kContinue;
  return true;
}

}  // namespace tray

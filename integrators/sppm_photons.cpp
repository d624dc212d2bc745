// SPPM's photon pass (Hachisuka & Jensen 2009, sec. 4.2; pbrt-v3 16.2.4-16.2.5): photons leave
// the lights (chosen by power, Light::sampleLe), scatter with the adjoint BSDF and Russian
// roulette, and every non-delta surface they reach after their first bounce gives its flux to
// the visible points whose radius contains it. (The first hit's light is the visible points'
// direct light, estimated by next-event estimation in the camera pass.)
//
// Deterministic for any thread count: photon i of iteration k draws from its own
// Sampler(i, k, seed); photons are traced in fixed chunks, each writing its hits in photon order;
// the hits are then sorted by (visible point, position in photon order) and each point sums its
// own in that order. No float is added in an order that threads decide.
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "integrators/absorption.h"
#include "integrators/sppm_integrator.h"

namespace tray {
namespace {

/// Veach 1997, sec. 5.3 (pbrt-v3's CorrectShadingNormal for importance): the adjoint BSDF with
/// shading normals is f(wo, wi) |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|), wo towards the light the
/// photon came from, wi where it goes. Returns the factor after f |wi.ns| / pdf; 0 where
/// undefined.
float shadingCorrection(const Vec3& wo, const Vec3& wi, const Vec3& ns, const Vec3& ng) {
  const float den = std::fabs(dot(wo, ng) * dot(wi, ns));
  return den > 0 ? std::fabs(dot(wo, ns) * dot(wi, ng)) / den : 0.0f;
}

}  // namespace

void SppmIntegrator::tracePhoton(int k, uint32_t i, const VisiblePointGrid& grid,
                                 std::span<const VisiblePoint> vps, std::vector<PhotonHit>& out,
                                 RayStats& rays) const {
  Sampler sampler(i, uint32_t(k), photonSeed_);
  const float uLight = sampler.next1D();
  const Vec2 u1 = sampler.next2D(), u2 = sampler.next2D();
  const EmittedRay e = emitter_.sample(uLight, u1, u2);
  if (!e.valid()) return;
  // The ray's weight L |cos| / (pmf pdfPos pdfDir), cos 1 for lights without a surface.
  const bool surface = dot(e.le.n, e.le.n) > 0;
  const float cosL = surface ? std::fabs(dot(e.le.n, e.le.ray.d)) : 1.0f;
  Color beta = e.le.L * (cosL / (e.pmf * e.le.pdfPos * e.le.pdfDir));
  if (!isFinite(beta) || isBlack(beta)) return;
  Ray ray = surface ? spawnRay(e.le.ray.o, e.le.n, e.le.ray.d, 0.0f) : e.le.ray;
  MediumStack media;
  int nullCrossings = 0;
  // depth: the photon's segments so far, including the one being traced. A photon reaching a
  // visible point of camera depth dc after `depth` segments makes a path of dc + depth
  // segments, which counts when it is within --max-depth (path's meaning).
  for (int depth = 1; depth < maxDepth_;) {
    Hit hit;
    ++rays.secondaryRays;
    if (!ctx_.accel.intersect(ray, hit)) return;
    const Color sigmaA = media.currentAbsorption();
    if (!isBlack(sigmaA)) beta *= transmittance(sigmaA, hit.t * length(ray.d));
    SurfaceVertex v;
    const VertexKind kind = vertices_.at(ray, hit, media, nullCrossings, v);
    if (kind == VertexKind::kPassed) continue;
    if (kind == VertexKind::kGaveUp || v.sm.unlit) return;
    const Bsdf bsdf = v.bsdf();
    if (depth > 1 && bsdf.hasNonDelta())
      grid.forEachNear(v.s.p, [&](uint32_t j) {
        if (vps[j].depth + depth <= maxDepth_) out.push_back({j, v.wo, beta});
      });
    if (depth + 1 >= maxDepth_) return;  // no visible point could take it any more
    const Vec3 u = sampler.next3D();
    const BsdfSample bs = bsdf.sampleImportance(v.wo, u.x, {u.y, u.z});
    if (!bs.valid()) return;
    const Color next =
        beta * bs.f *
        (std::fabs(dot(bs.wi, v.n)) / bs.pdf * shadingCorrection(v.wo, bs.wi, v.n, v.s.ng));
    if (!isFinite(next) || isBlack(next)) return;
    // Russian roulette keeping the weight's size (pbrt-v3 16.2.4): continue with probability
    // min(1, |next| / |beta|), dividing by it.
    const float q = std::max(0.0f, 1.0f - maxComponent(next) / maxComponent(beta));
    if (sampler.next1D() < q) return;
    beta = next / (1.0f - q);
    if (bs.transmission) SurfaceVertices::transmit(v, media);
    setSpawnRay(ray, v.s.p, v.s.ng, bs.wi, v.s.time);
    ++depth;
  }
}

void SppmIntegrator::photonPass(int k, std::span<const VisiblePoint> vps,
                                std::span<const SppmPixel> stats, std::span<Color> phi,
                                std::span<uint32_t> m, RayStats& rays) const {
  const size_t n = vps.size();
  std::vector<Vec3> points(n);
  std::vector<float> radii(n);
  tbb::parallel_for(size_t(0), n, [&](size_t p) {
    points[p] = vps[p].p;
    radii[p] = vps[p].bsdf ? stats[p].radius : 0.0f;
    phi[p] = Color(0.0f);
    m[p] = 0;
  });
  const VisiblePointGrid grid(points, radii);
  if (grid.entryCount() == 0 || photons_ == 0) return;

  // Photons in fixed chunks, each chunk's hits in photon order.
  const uint32_t chunks = (photons_ + kPhotonChunk - 1) / kPhotonChunk;
  std::vector<std::vector<PhotonHit>> hits(chunks);
  tbb::combinable<RayStats> local;
  tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t c) {
    const uint32_t end = std::min(photons_, (c + 1) * kPhotonChunk);
    for (uint32_t i = c * kPhotonChunk; i < end; ++i)
      tracePhoton(k, i, grid, vps, hits[c], local.local());
  });
  local.combine_each([&](const RayStats& r) { rays += r; });

  // Every hit's place in photon order, then sorted by (visible point, place): unique keys.
  std::vector<size_t> offset(chunks + 1, 0);
  for (uint32_t c = 0; c < chunks; ++c) offset[c + 1] = offset[c] + hits[c].size();
  if (offset.back() >= (uint64_t(1) << 32))
    throw Error("sppm: too many photon hits in one iteration (lower --photons or --sppm-radius)",
                Error::Kind::kRender);
  std::vector<uint64_t> keys(offset.back());
  tbb::parallel_for(uint32_t(0), chunks, [&](uint32_t c) {
    for (size_t h = 0; h < hits[c].size(); ++h)
      keys[offset[c] + h] = uint64_t(hits[c][h].vp) << 32 | (offset[c] + h);
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  std::vector<size_t> first(n + 1, 0);  // keys[first[j] .. first[j + 1]) are point j's
  for (uint64_t key : keys) ++first[(key >> 32) + 1];
  for (size_t j = 0; j < n; ++j) first[j + 1] += first[j];
  auto hitAt = [&](uint64_t key) -> const PhotonHit& {
    const size_t place = size_t(key & 0xffffffffu);
    const size_t c =
        size_t(std::upper_bound(offset.begin(), offset.end(), place) - offset.begin()) - 1;
    return hits[c][place - offset[c]];
  };
  // Each point on one thread: its Bsdf (whose lobe probabilities are cached) is not shared.
  tbb::parallel_for(size_t(0), n, [&](size_t j) {
    if (first[j] == first[j + 1]) return;
    const VisiblePoint& vp = vps[j];
    Color sum(0.0f);
    for (size_t e = first[j]; e < first[j + 1]; ++e) {
      const PhotonHit& h = hitAt(keys[e]);
      float pdf;
      sum += h.beta * vp.bsdf->eval(vp.wo, h.wi, pdf);
    }
    phi[j] = sum;
    m[j] = uint32_t(first[j + 1] - first[j]);
  });
}

}  // namespace tray

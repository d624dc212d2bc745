// SPPM's camera pass (Hachisuka & Jensen 2009, sec. 4.1; pbrt-v3 16.2.3): one camera path per
// pixel and iteration, followed through delta (mirror, smooth glass) bounces to its first
// vertex with a non-delta lobe, the visible point; emission met on the way and direct light
// there are added to the pixel at once.
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "core/camera_culling.h"
#include "core/front_face.h"
#include "integrators/absorption.h"
#include "integrators/path_vertex_lanes.h"
#include "integrators/sppm_integrator.h"

namespace tray {

void SppmIntegrator::cameraPass(const FrameTask& task, int k, std::span<VisiblePoint> vps,
                                std::span<SppmPixel> stats, std::span<FramePixel> pixels,
                                RayStats& rays) const {
  tbb::combinable<RayStats> local;  // integer counters: their sum has no order
  tbb::parallel_for(size_t(0), pixels.size(), [&](size_t p) {
    const int x = task.x0 + int(p % size_t(task.width));
    const int y = task.y0 + int(p / size_t(task.width));
    PrimaryHit seen;
    const Color L = traceCamera(x, y, k, vps[p], stats[p], seen, local.local());
    SppmPixel& s = stats[p];
    FramePixel& out = pixels[p];
    ++out.samples;
    s.hits += seen.hit;
    if (k == 0) out.first = seen;
    if (task.wantsIds)
      out.coverage.add(seen.hit ? seen.objectId : -1, seen.hit ? seen.materialId : -1, 1.0);
    if (isFinite(L)) {
      s.ld[0] += L.x, s.ld[1] += L.y, s.ld[2] += L.z;
    } else {
      local.local().countNonFinite(L);
    }
  });
  local.combine_each([&](const RayStats& r) { rays += r; });
}

Color SppmIntegrator::traceCamera(int x, int y, int k, VisiblePoint& vp, SppmPixel& pixel,
                                  PrimaryHit& seen, RayStats& rays) const {
  Sampler sampler = this->sampler(x, y, k);
  Vec2 offset;  // every camera sample weighs 1: SPPM's pixel is a box over its samples
  Ray ray = cameraRay(x, y, k, sampler, offset);
  ++rays.cameraRays;
  Color L(0.0f), beta(1.0f);
  MediumStack media;
  int nullCrossings = 0;
  float along = 0;  // the path's length so far, for the first radius
  const Vec3 origin = ray.o;
  for (int depth = 1;;) {
    Hit hit;
    // The camera's ray passes single-sided back faces (core/camera_culling.h).
    const bool found = depth == 1 && nullCrossings == 0
                           ? intersectCameraRay(ctx_.accel, ctx_.scene, ray, hit)
                           : ctx_.accel.intersect(ray, hit);
    if (!found) {
      if (depth == 1 && transparentBackground()) break;
      const Vec3 dir = normalize(ray.d);
      if (isBlack(media.currentAbsorption()))
        for (int i : lights_.infinite()) L += beta * lights_.Le(i, dir);
      break;
    }
    const Color sigmaA = media.currentAbsorption();
    if (!isBlack(sigmaA)) beta *= transmittance(sigmaA, hit.t * length(ray.d));
    along += hit.t * length(ray.d);
    SurfaceVertex v;
    const VertexKind kind = vertices_.at(ray, hit, media, nullCrossings, v);
    if (kind == VertexKind::kPassed) continue;
    if (kind == VertexKind::kGaveUp) break;
    const SurfacePoint& s = v.s;
    if (!seen.hit) {
      seen.hit = true;
      seen.depth = length(s.p - origin);
      seen.position = s.p;
      seen.normal = v.sm.n;
      seen.albedo = v.sm.baseColor;
      seen.objectId = ctx_.scene.objectId(s.primitive, s.instance);
      seen.materialId = s.material;
      seen.primitive = s.primitive, seen.instance = s.instance, seen.time = s.time;
    }
    if (v.sm.unlit) {  // KHR_materials_unlit: the base colour leaves as is
      L += beta * v.sm.baseColor;
      break;
    }
    // Every vertex before the visible point is a delta bounce: emission there has no other
    // estimator to be weighed against.
    if (!isBlack(v.sm.emissive) && emitsToward(s.front, -ray.d, v.m->doubleSided))
      L += beta * v.sm.emissive;
    if (depth + 1 > maxDepth_) break;
    const Bsdf bsdf = v.bsdf();
    if (bsdf.hasNonDelta()) {
      L += beta * directLight(v, bsdf, media, sampler, rays);
      vp.p = s.p, vp.wo = v.wo, vp.beta = beta, vp.depth = depth;
      vp.bsdf.emplace(bsdf);
      if (!(pixel.radius > 0)) pixel.radius = initialRadius(x, y, along);
      break;
    }
    const Vec3 u = sampler.next3D();
    const BsdfSample bs = bsdf.sample(v.wo, u.x, {u.y, u.z});
    if (!bs.valid()) break;
    beta = scatteredThroughput(beta, bs.f, bs.wi, v.n, bs.pdf);
    if (!isFinite(beta) || isBlack(beta)) break;
    if (bs.transmission) SurfaceVertices::transmit(v, media);
    setSpawnRay(ray, s.p, s.ng, bs.wi, s.time);
    ++rays.secondaryRays;
    ++depth;
  }
  return L;
}

Color SppmIntegrator::directLight(const SurfaceVertex& v, const Bsdf& bsdf,
                                  const MediumStack& media, Sampler& sampler,
                                  RayStats& rays) const {
  if (lights_.empty()) return Color(0.0f);
  const SurfacePoint& s = v.s;
  LightSampleContext here;
  here.p = s.p, here.n = v.n;
  here.transmits = bsdf.transmits();
  here.belowMatters = bsdf.transmits() || !(dot(v.wo, v.n) > 0) || v.sm.clearcoat > 0;
  const Vec3 u = sampler.next3D();  // the light choice and the point on it
  const LightSample ls = lights_.sample(here, u.x, {u.y, u.z});
  if (!ls.valid() || isBlack(ls.L)) return Color(0.0f);
  float pdf;
  Color f = bsdf.eval(v.wo, ls.wi, pdf) * std::fabs(dot(ls.wi, v.n));
  if (isBlack(f)) return Color(0.0f);
  const Ray shadow =
      ls.infinite ? spawnRay(s.p, s.ng, ls.wi, s.time) : spawnRayTo(s.p, s.ng, ls.p, s.time);
  ++rays.shadowRays;
  if (ctx_.accel.occluded(shadow)) return Color(0.0f);
  // The shadow ray crosses the medium on its side of the surface (KHR_materials_volume).
  const Color sigma = v.refractive && dot(ls.wi, v.n) < 0
                          ? farSideAbsorption(media, s.material, *v.m, s.frontFace)
                          : media.currentAbsorption();
  if (!isBlack(sigma)) f *= ls.infinite ? Color(0.0f) : transmittance(sigma, length(ls.p - s.p));
  return neeContribution(Color(1.0f), f, ls.L, 1.0f, ls.pdf);
}

}  // namespace tray

#include "integrators/bdpt_tracer.h"

#include <cmath>

#include "core/camera_culling.h"
#include "core/error.h"
#include "core/front_face.h"
#include "integrators/absorption.h"
#include "integrators/path_vertex_lanes.h"
#include "integrators/surface_rules.h"

namespace tray {
namespace {

CameraImportance importanceOf(const RenderContext& ctx) {
  std::optional<CameraImportance> c = CameraImportance::of(ctx.camera, ctx.width, ctx.height);
  if (!c)
    throw Error(
        "bdpt: the camera must be a pinhole perspective or an orthographic one with a rigid "
        "transform (a thin lens, --lens-radius > 0, and scaled cameras are not supported)");
  return *c;
}

}  // namespace

BdptTracer::BdptTracer(const RenderContext& ctx)
    : ctx_(ctx),
      maxDepth_(ctx.settings.getInt("max-depth")),
      camera_(importanceOf(ctx)),
      lights_(ctx.scene, lightSamplerKind(ctx.settings.getString("light-sampler")),
              triangleSampling(ctx.settings.getString("triangle-sampling"))),
      emission_(lights_),
      materials_(ctx.scene, ctx.camera, ctx.settings.getInt("spp")) {
  if (ctx.scene.moving() || !ctx.camera.desc().motion.empty())
    throw Error("bdpt: motion blur (moving objects or camera) is not supported");
}

bool BdptTracer::surfaceVertex(const Ray& ray, const Hit& hit, MediumStack& media,
                               BdptVertex& v) const {
  // As path's vertex (integrators/path_estimator.cpp, step): nested dielectrics pass a surface
  // of a medium that is not in effect straight by; eta from the medium stack.
  v.s = ctx_.scene.surface(ray, hit);
  const SurfacePoint& s = v.s;
  v.m = &ctx_.scene.material(s.material);
  const Material& m = *v.m;
  v.refractive = isRefractive(m);
  v.eta = m.ior / media.currentIor();
  v.sigmaA = media.currentAbsorption();
  v.sigmaFar = v.sigmaA;
  if (v.refractive) {
    const MediumStack::Interface iface = media.interface(s.material, m, s.frontFace);
    if (!iface.real) {
      media.cross(s.material, m, s.frontFace);
      return false;
    }
    v.eta = iface.etaT / iface.etaI;
    v.sigmaFar = farSideAbsorption(media, s.material, m, s.frontFace);
  }
  v.kind = BdptVertex::Kind::kSurface;
  v.sm = materials_.evaluate(hit, s);
  hideOuterLayersInside(v.sm, v.refractive, s.frontFace);
  v.p = s.p;
  v.ng = s.ng;
  v.n = s.frontFace ? v.sm.n : -v.sm.n;
  v.wo = -normalize(ray.d);
  v.unlit = v.sm.unlit;
  v.nonDelta = !v.unlit && v.bsdf().hasNonDelta();
  if (!isBlack(v.sm.emissive) && emitsToward(s.front, v.wo, m.doubleSided)) v.Le = v.sm.emissive;
  v.light = lights_.lightAt(hit.primitive, hit.triangle);
  return true;
}

void BdptTracer::walk(Ray ray, Color beta, float pdfDir, Sampler& sampler, RayStats& stats,
                      Mode mode, size_t maxVertices, MediumStack media, PrimaryHit* primary,
                      std::vector<BdptVertex>& path) const {
  int nullCrossings = 0;
  while (path.size() < maxVertices) {
    Hit hit;
    // The camera's ray passes single-sided back faces (core/camera_culling.h).
    const bool found = mode == Mode::kRadiance && path.size() == 1 && nullCrossings == 0
                           ? intersectCameraRay(ctx_.accel, ctx_.scene, ray, hit)
                           : ctx_.accel.intersect(ray, hit);
    const Color sigmaA = media.currentAbsorption();
    const bool absorbing = !isBlack(sigmaA);
    if (!found) {
      // Escaped: the camera subpath ends on the infinite lights (s = 0); lost inside an open
      // absorbing mesh, it ends with nothing (transmittance 0), as path's.
      if (mode == Mode::kImportance || absorbing || lights_.infinite().empty()) return;
      BdptVertex v;
      v.kind = BdptVertex::Kind::kEnvironment;
      v.infinite = true;
      const Vec3 d = normalize(ray.d);
      v.dir = -d;
      v.beta = beta;
      v.pdfFwd = pdfDir;
      for (int i : lights_.infinite()) v.Le += lights_.Le(i, d);
      v.light = lights_.infinite().front();
      path.push_back(v);
      return;
    }
    if (absorbing) {
      beta *= transmittance(sigmaA, hit.t * length(ray.d));
      if (isBlack(beta)) return;
    }
    BdptVertex v;
    if (!surfaceVertex(ray, hit, media, v)) {
      if (++nullCrossings > kMaxNullCrossings) return;
      setSpawnRay(ray, v.s.p, v.s.ng, ray.d, v.s.time);
      ++stats.secondaryRays;
      continue;
    }
    const BdptVertex& prev = path.back();
    v.beta = beta;
    v.pdfFwd = prev.kind == BdptVertex::Kind::kCamera ? camera_.pdfFirst(v.p, v.ng)
               : prev.infinite ? pdfDir * std::fabs(dot(v.ng, ray.d) / length(ray.d))
                               : toArea(pdfDir, prev, v);
    if (primary && !primary->hit)
      recordPrimaryHit(*primary, ctx_.scene, v.s, path.front().p, v.sm.n, v.sm.baseColor);
    path.push_back(v);
    BdptVertex& cur = path.back();
    if (cur.unlit || path.size() >= maxVertices) return;
    const Vec3 u = sampler.next3D();  // the lobe choice, then the direction
    const Bsdf bsdf = cur.bsdf();
    const BsdfSample bs = mode == Mode::kRadiance ? bsdf.sample(cur.wo, u.x, {u.y, u.z})
                                                  : bsdf.sampleImportance(cur.wo, u.x, {u.y, u.z});
    if (!bs.valid()) return;
    beta = scatteredThroughput(beta, bs.f, bs.wi, cur.n, bs.pdf);
    // Importance leaving along wi (Veach 1997 §5.3).
    if (mode == Mode::kImportance) beta *= shadingCorrection(cur, cur.wo, bs.wi);
    if (!isFinite(beta) || isBlack(beta)) return;
    // A delta choice has no density either way (pbrt-v3 16.3.1: both 0, remapped to 1).
    float pdfRev = 0;
    if (bs.delta) {
      cur.delta = true;
      pdfDir = 0;
    } else {
      pdfDir = bs.pdf;
      pdfRev = pdfDirAt(cur, bs.wi, cur.wo);
    }
    BdptVertex& before = path[path.size() - 2];
    before.pdfRev = toArea(pdfRev, cur, before);
    if (bs.transmission && cur.refractive) media.cross(cur.s.material, *cur.m, cur.s.frontFace);
    setSpawnRay(ray, cur.s.p, cur.s.ng, bs.wi, cur.s.time);
    ++stats.secondaryRays;
  }
}

void BdptTracer::cameraSubpath(const Ray& ray, Sampler& sampler, RayStats& stats,
                               PrimaryHit* primary, std::vector<BdptVertex>& out) const {
  out.clear();
  BdptVertex z0;
  z0.kind = BdptVertex::Kind::kCamera;
  z0.p = ray.o;
  z0.beta = Color(1.0f);
  z0.pdfFwd = 1;
  out.push_back(z0);
  walk(ray, Color(1.0f), 0.0f, sampler, stats, Mode::kRadiance, size_t(maxDepth_) + 1, {}, primary,
       out);
}

void BdptTracer::lightSubpath(Sampler& sampler, RayStats& stats,
                              std::vector<BdptVertex>& out) const {
  out.clear();
  if (lights_.empty() || maxDepth_ < 2) return;
  const Vec3 a = sampler.next3D();  // the light choice and the origin, then the direction
  const Vec2 u2 = sampler.next2D();
  const EmittedRay e = emission_.sample(a.x, {a.y, a.z}, u2);
  if (!e.valid()) return;
  const Light& light = lights_.light(size_t(e.light));
  BdptVertex y0;
  y0.kind = BdptVertex::Kind::kLight;
  y0.light = e.light;
  y0.deltaLight = light.isDelta();
  y0.infinite = (light.flags() & (kLightInfinite | kLightDeltaDirection)) != 0;
  y0.p = e.le.ray.o;
  y0.ng = e.le.n;
  y0.dir = e.le.ray.d;
  y0.beta = e.le.L / (e.pmf * e.le.pdfPos);
  // Choice x position; a light at infinity: choice x direction (pbrt-v3 16.3.1).
  y0.pdfFwd = y0.infinite ? e.pmf * e.le.pdfDir : e.pmf * e.le.pdfPos;
  out.push_back(y0);
  const float cosine = e.le.n == Vec3(0.0f) ? 1.0f : std::fabs(dot(e.le.n, e.le.ray.d));
  const Color beta = e.le.L * (cosine / (e.pmf * e.le.pdfPos * e.le.pdfDir));
  Ray ray = e.le.ray;
  if (e.le.n != Vec3(0.0f)) setSpawnRay(ray, e.le.ray.o, e.le.n, e.le.ray.d, 0.0f);
  // The first hit's density: the direction's (per solid angle) from a finite light; the
  // origin's on the disk, projected, from one at infinity (walk reads it so).
  walk(ray, beta, y0.infinite ? e.le.pdfPos : e.le.pdfDir, sampler, stats, Mode::kImportance,
       size_t(maxDepth_), {}, nullptr, out);
}

float BdptTracer::pdfDirAt(const BdptVertex& v, const Vec3& from, const Vec3& to) const {
  return v.bsdfFacing(from).pdf(from, to);
}

float BdptTracer::pdfLightOrigin(const BdptVertex& v, const Vec3& towardTo) const {
  if (v.infinite) {
    // Every light at infinity could have emitted along v.dir (pbrt-v3's InfiniteLightDensity).
    float pdf = 0;
    for (int i : lights_.infinite())
      pdf += emission_.pmf(i) * emission_.pdfLe(i, {}, {}, v.dir).dir;
    return pdf;
  }
  if (v.light < 0) return 0.0f;
  return emission_.pmf(v.light) * emission_.pdfLe(v.light, v.p, v.emitNormal(), towardTo).pos;
}

float BdptTracer::pdfLightTo(const BdptVertex& v, const BdptVertex& to) const {
  if (v.light < 0) return 0.0f;
  if (v.infinite) {
    // Uniform over the disk facing the scene (Light::sampleLe), projected onto `to`.
    const float pos = emission_.pdfLe(v.light, {}, {}, v.dir).pos;
    return to.ng == Vec3(0.0f) ? pos : pos * std::fabs(dot(to.ng, v.dir));
  }
  const Vec3 w = directionTo(v, to);
  return toArea(emission_.pdfLe(v.light, v.p, v.emitNormal(), w).dir, v, to);
}

bool BdptTracer::visible(const BdptVertex& a, const BdptVertex& b) const {
  // From a surface point or the camera to a finite point, offset at the surface.
  const Vec3 ng = a.onSurface() ? a.s.ng : Vec3(0.0f);
  const float time = a.onSurface() ? a.s.time : 0.0f;
  if (b.infinite) return !ctx_.accel.occluded(spawnRay(a.p, ng, -b.dir, time));
  return !ctx_.accel.occluded(spawnRayTo(a.p, ng, b.p, time));
}

}  // namespace tray

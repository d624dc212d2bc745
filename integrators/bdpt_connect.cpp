// The strategies of bidirectional path tracing and their MIS weights (Veach 1997 §10.2-10.3;
// the structure of pbrt-v3 16.3.3-16.3.4: ConnectBDPT, MISWeight).
#include <cmath>

#include "integrators/absorption.h"
#include "integrators/bdpt_tracer.h"
#include "integrators/surface_rules.h"

namespace tray {

void BdptTracer::setConnectionPdfs(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera,
                                   int s, int t) const {
  BdptVertex* z = t > 0 ? &camera[size_t(t - 1)] : nullptr;
  BdptVertex* zBefore = t > 1 ? &camera[size_t(t - 2)] : nullptr;
  BdptVertex* y = s > 0 ? &light[size_t(s - 1)] : nullptr;
  BdptVertex* yBefore = s > 1 ? &light[size_t(s - 2)] : nullptr;
  // The camera side's last vertex as the light side would have made it, and the one before.
  if (z && t > 1) {
    if (s == 0)
      z->pdfRev = pdfLightOrigin(*z, directionTo(*z, *zBefore));
    else if (s == 1)
      z->pdfRev = pdfLightTo(*y, *z);
    else
      z->pdfRev = toArea(pdfDirAt(*y, y->wo, directionTo(*y, *z)), *y, *z);
  }
  if (zBefore) {
    if (s == 0)
      zBefore->pdfRev = pdfLightTo(*z, *zBefore);
    else
      zBefore->pdfRev = toArea(pdfDirAt(*z, directionTo(*z, *y), z->wo), *z, *zBefore);
  }
  // The light side's last vertex as the camera side would have made it, and the one before.
  if (y) {
    if (t == 1)
      y->pdfRev = camera_.pdfFirst(y->p, y->ng);
    else
      y->pdfRev = toArea(pdfDirAt(*z, z->wo, directionTo(*z, *y)), *z, *y);
  }
  if (yBefore) yBefore->pdfRev = toArea(pdfDirAt(*y, directionTo(*y, *z), y->wo), *y, *yBefore);
}

float BdptTracer::misWeight(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int s,
                            int t) const {
  // Only (0, 2) makes a two-vertex path: (1, 1) is not used and a pinhole cannot be hit.
  if (s + t == 2) return 1.0f;
  // The ratio walk of pbrt-v3 16.3.4: p_i / p_s for every other strategy i that makes the same
  // path, multiplied out one vertex at a time from the connection; the power heuristic sums
  // their squares. A delta choice's density (0) is remapped to 1: it cancels in the ratios,
  // and the strategies that would connect at that vertex are left out.
  const auto remap = [](float f) { return f != 0 ? f : 1.0f; };
  // The connection's two vertices are not delta choices, whatever their sampling did next.
  const auto deltaAt = [&](const std::vector<BdptVertex>& path, int i, int last) {
    return i != last && path[size_t(i)].delta;
  };
  float sum = 0, ratio = 1;
  for (int i = t - 1; i > 0; --i) {  // the strategy with t' = i camera vertices
    ratio *= remap(camera[size_t(i)].pdfRev) / remap(camera[size_t(i)].pdfFwd);
    const bool unused = i == 1 && s + t - 1 == 1;  // (1, 1)
    if (!deltaAt(camera, i, t - 1) && !deltaAt(camera, i - 1, t - 1) && !unused)
      sum += ratio * ratio;
  }
  ratio = 1;
  for (int i = s - 1; i >= 0; --i) {  // the strategy with s' = i light vertices
    ratio *= remap(light[size_t(i)].pdfRev) / remap(light[size_t(i)].pdfFwd);
    // s' = 0 must hit the light: not a point, spot or directional one.
    const bool beforeDelta = i > 0 ? deltaAt(light, i - 1, s - 1) : light[0].deltaLight;
    if (!deltaAt(light, i, s - 1) && !beforeDelta) sum += ratio * ratio;
  }
  return 1.0f / (1.0f + sum);
}

float BdptTracer::weight(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int s,
                         int t) const {
  // Emitters seen directly have one strategy, (0, 2), in every family.
  if (s == 0 && t == 2) return 1.0f;
  switch (strategies_) {
    case BdptStrategies::kS0:
      return s == 0 ? 1.0f : 0.0f;
    case BdptStrategies::kS1:
      return s == 1 ? 1.0f : 0.0f;
    case BdptStrategies::kT1:
      return t == 1 ? 1.0f : 0.0f;
    case BdptStrategies::kAll:
      break;
  }
  // The connection's densities hold for this strategy only: the walk's are put back after
  // (pbrt-v3's ScopedAssignment), as the next strategy reads them.
  float* saved[4] = {t > 0 ? &camera[size_t(t - 1)].pdfRev : nullptr,
                     t > 1 ? &camera[size_t(t - 2)].pdfRev : nullptr,
                     s > 0 ? &light[size_t(s - 1)].pdfRev : nullptr,
                     s > 1 ? &light[size_t(s - 2)].pdfRev : nullptr};
  float values[4];
  for (int i = 0; i < 4; ++i) values[i] = saved[i] ? *saved[i] : 0.0f;
  setConnectionPdfs(light, camera, s, t);
  const float w = misWeight(light, camera, s, t);
  for (int i = 0; i < 4; ++i)
    if (saved[i]) *saved[i] = values[i];
  return w;
}

Color BdptTracer::connectS0(std::vector<BdptVertex>& camera, int t) const {
  BdptVertex& z = camera[size_t(t - 1)];
  if (isBlack(z.Le)) return Color(0.0f);
  const Color L = z.beta * z.Le;
  // An emitter outside the light set: no other strategy makes this path.
  if (z.light < 0 && strategies_ == BdptStrategies::kAll) return L;
  std::vector<BdptVertex> none;
  const float w = weight(none, camera, 0, t);
  return w > 0 ? L * w : Color(0.0f);
}

Color BdptTracer::connectS1(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int t,
                            Sampler& sampler, RayStats& stats) const {
  BdptVertex& z = camera[size_t(t - 1)];
  // Next-event estimation as path's (integrators/path_estimator.cpp, nextEvent): the LightSet's
  // choice at the receiver, then a point or direction on the light.
  const Vec3 u = sampler.next3D();
  const Bsdf bsdf = z.bsdf();
  LightSampleContext here;
  here.p = z.p, here.n = z.n, here.transmits = bsdf.transmits();
  here.belowMatters = belowMatters(bsdf.transmits(), z.wo, z.n, z.sm);
  float pmf;
  const int i = lights_.choose(here, u.x, pmf);
  if (i < 0 || !(pmf > 0)) return Color(0.0f);
  const LightSample ls = lights_.sampleChosen(i, pmf, here, {u.y, u.z});
  if (!ls.valid() || isBlack(ls.L)) return Color(0.0f);
  Color f = bsdf.eval(z.wo, ls.wi) * std::fabs(dot(ls.wi, z.n));
  if (isBlack(f)) return Color(0.0f);
  const Light& l = lights_.light(size_t(i));
  light.resize(1);
  BdptVertex& y = light[0];
  y = BdptVertex();
  y.kind = BdptVertex::Kind::kLight;
  y.light = i;
  y.deltaLight = l.isDelta();
  y.infinite = (l.flags() & (kLightInfinite | kLightDeltaDirection)) != 0;
  y.dir = -ls.wi;
  y.p = ls.p;
  ++stats.shadowRays;
  if (l.flags() & kLightArea) {
    // The light's normal at the point (its emission densities need it): found by tracing
    // toward it, which is the visibility test too.
    Ray r = spawnRay(z.p, z.s.ng, ls.wi, z.s.time);
    const float dist = length(ls.p - r.o);
    r.tmax = dist * 1.001f;
    Hit hit;
    if (!ctx_.accel.intersect(r, hit) || lights_.lightAt(hit.primitive, hit.triangle) != i)
      return Color(0.0f);
    const SurfacePoint sp = ctx_.scene.surface(r, hit);
    y.p = sp.p;
    y.ng = sp.front;
  } else if (!visible(z, y)) {
    return Color(0.0f);
  }
  const Color sigma = z.absorptionToward(ls.wi);
  if (!isBlack(sigma)) f *= y.infinite ? Color(0.0f) : transmittance(sigma, length(y.p - z.p));
  const Color L = z.beta * f * ls.L / ls.pdf;
  if (isBlack(L)) return Color(0.0f);
  // MIS: the vertex's density as a light subpath's origin (the emission sampler's), whatever
  // chose it here: the weights need one density per vertex for every strategy, and any such
  // set gives weights that sum to 1 (Veach 1997 §9.2); see docs/bdpt.md.
  y.pdfFwd = pdfLightOrigin(y, directionTo(y, z));
  const float w = weight(light, camera, 1, t);
  return L * w;
}

Color BdptTracer::connectInner(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera,
                               int s, int t, RayStats& stats) const {
  BdptVertex& y = light[size_t(s - 1)];
  BdptVertex& z = camera[size_t(t - 1)];
  if (!y.connectible() || !z.connectible() || !y.onSurface() || !z.onSurface()) return Color(0.0f);
  const Vec3 d = y.p - z.p;
  const float dist2 = dot(d, d);
  if (!(dist2 > 0)) return Color(0.0f);
  const float dist = std::sqrt(dist2);
  const Vec3 w = d / dist;  // from z toward y
  float pdf;
  const Color fz = z.bsdf().eval(z.wo, w);
  if (isBlack(fz)) return Color(0.0f);
  const Color fy = y.bsdf().evalImportance(y.wo, -w, pdf) * shadingCorrection(y, y.wo, -w);
  if (isBlack(fy)) return Color(0.0f);
  // The geometry term with shading cosines, as the subpaths' throughputs carry them.
  const float G = std::fabs(dot(z.n, w)) * std::fabs(dot(y.n, w)) / dist2;
  Color L = z.beta * fz * fy * y.beta * G;
  const Color sigma = z.absorptionToward(w);
  if (!isBlack(sigma)) L *= transmittance(sigma, dist);
  if (isBlack(L)) return Color(0.0f);
  ++stats.shadowRays;
  if (!visible(z, y)) return Color(0.0f);
  return L * weight(light, camera, s, t);
}

bool BdptTracer::connectToCamera(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera,
                                 int s, RayStats& stats, Splat& out) const {
  BdptVertex& y = light[size_t(s - 1)];
  if (!y.onSurface() || !y.connectible()) return false;
  const std::optional<CameraConnection> c = camera_.connect(y.p);
  if (!c) return false;
  float pdf;
  const Color f = y.bsdf().evalImportance(y.wo, c->wi, pdf) * shadingCorrection(y, y.wo, c->wi);
  if (isBlack(f)) return false;
  Color L = y.beta * f * (std::fabs(dot(y.n, c->wi)) * c->weight);
  const Color sigma = y.absorptionToward(c->wi);
  if (!isBlack(sigma)) L *= transmittance(sigma, c->distance);
  if (isBlack(L)) return false;
  ++stats.shadowRays;
  camera[0].p = c->target;
  if (!visible(y, camera[0])) return false;
  const float w = weight(light, camera, s, 1);
  if (!(w > 0)) return false;
  out = {c->raster, L * w};
  return true;
}

}  // namespace tray

namespace tray {
namespace {

/// Per-thread storage for a sample's subpaths, reused (cleared) by every sample: no state
/// passes from one sample to the next.
struct Subpaths {
  std::vector<BdptVertex> camera, light, scratch;
};
thread_local Subpaths tlsPaths;

}  // namespace

Color BdptTracer::cameraEstimate(const Ray& ray, Sampler& sampler, RayStats& stats,
                                 PrimaryHit* primary) const {
  Subpaths& p = tlsPaths;
  if (maxDepth_ == 0) return Color(0.0f);
  cameraSubpath(ray, sampler, stats, primary, p.camera);
  const bool all = strategies_ == BdptStrategies::kAll;
  if (all)
    lightSubpath(sampler, stats, p.light);
  else
    p.light.clear();
  Color L(0.0f);
  for (int t = 2; t <= int(p.camera.size()); ++t) {
    const BdptVertex& z = p.camera[size_t(t - 1)];
    // KHR_materials_unlit: only the camera finds it (path's rule: no MIS).
    if (z.unlit) {
      if (all || strategies_ == BdptStrategies::kS0 || t == 2) L += z.beta * z.sm.baseColor;
      continue;
    }
    if (all || strategies_ == BdptStrategies::kS0 || t == 2) L += connectS0(p.camera, t);
    if (!z.onSurface() || !z.connectible()) continue;
    // Segments s + t - 1 at most maxDepth (path's depth).
    if (t <= maxDepth_ && (all || strategies_ == BdptStrategies::kS1))
      L += connectS1(p.scratch, p.camera, t, sampler, stats);
    if (!all) continue;
    const int maxS = std::min(int(p.light.size()), maxDepth_ + 1 - t);
    for (int s = 2; s <= maxS; ++s) L += connectInner(p.light, p.camera, s, t, stats);
  }
  return L;
}

void BdptTracer::lightEstimate(Sampler& sampler, RayStats& stats, std::vector<Splat>& out) const {
  Subpaths& p = tlsPaths;
  lightSubpath(sampler, stats, p.light);
  if (p.light.size() < 2) return;
  p.camera.resize(1);
  BdptVertex& z0 = p.camera[0];
  z0 = BdptVertex();
  z0.kind = BdptVertex::Kind::kCamera;
  // z0.p: where each connection ends on the camera (connectToCamera sets it).
  z0.pdfFwd = 1;
  for (int s = 2; s <= std::min(int(p.light.size()), maxDepth_); ++s) {
    Splat splat;
    if (connectToCamera(p.light, p.camera, s, stats, splat)) out.push_back(splat);
  }
}

}  // namespace tray

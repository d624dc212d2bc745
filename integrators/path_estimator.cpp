#include "integrators/path_estimator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <new>

#include "core/front_face.h"
#include "core/unbuilt.h"
#include "integrators/absorption.h"
#include "integrators/path_vertex_lanes.h"
#include "integrators/surface_rules.h"
#include "materials/bsdf.h"
#include "textures/shading.h"

namespace tray {

/// The first surface a camera ray met, for the AOVs and Cryptomatte.
void PathEstimator::recordPrimary(PrimaryHit& primary, const PathState& st, const SurfacePoint& s,
                                  const Vec3& shadingN, const Color& albedo) const {
  recordPrimaryHit(primary, ctx_.scene, s, st.cameraOrigin, shadingN, albedo);
}

/// The scattering vertex being shaded: what NEE and BSDF sampling both read.
struct PathEstimator::Vertex {
  /// The caller's surface when it has one (the wavefront's, computed in SIMD): read where it
  /// is, not copied (76 bytes per vertex). Otherwise built here in place (not assigned from a
  /// returned temporary: a store-forwarding stall, see setSpawnRay in core/ray.h).
  Vertex(const Scene& scene, const Ray& ray, const Hit& hit, const SurfacePoint* known)
      : s(known ? *known : *new (&own.value) SurfacePoint(scene.surface(ray, hit))) {}
  Unbuilt<SurfacePoint> own;  ///< built only when the caller has no surface
  const SurfacePoint& s;
  const Material* m;
  Vec3 n;   ///< shading normal on the side the ray arrived from
  Vec3 wo;  ///< towards where the ray came from
  bool refractive;
  Color sigmaA;  ///< absorption of the medium the arriving segment crossed
  /// What light sampling knows of the receiver; BSDF sampling's MIS weights use the same.
  LightSampleContext here;
  /// defer() chose `light` with probability lightPmf from `here` and the first draw, then left
  /// the vertex to the scalar code (another kind of light): nextEvent samples that choice.
  bool lightChosen = false;
  int light;
  float lightPmf;
  /// What the light choice here gave of LightSet::pmf(here, escapeLight()), or -1.
  float escapePmf = -1;
};

/// The vertex's 3D draws: those made ahead while they last, then the sampler's own.
struct PathEstimator::VertexDraws {
  Sampler& sampler;
  const Vec3* ahead[2];
  int used = 0;
  Vec3 next3D() {
    if (used < 2 && ahead[used]) {
      sampler.skip3D();
      return *ahead[used++];
    }
    return sampler.next3D();
  }
};

PathEstimator::PathEstimator(const RenderContext& ctx)
    : ctx_(ctx),
      maxDepth_(ctx.settings.getInt("max-depth")),
      rouletteDepth_(ctx.settings.getInt("rr-depth")),
      sqrtSurvival_(ctx.settings.getString("rr-survival") == "sqrt"),
      clampIndirect_(ctx.settings.getFloat("clamp-indirect")),
      debugNan_(ctx.settings.getBool("debug-nan")),
      absorbingMedia_(std::any_of(ctx.scene.materials.begin(), ctx.scene.materials.end(),
                                  [](const Material& m) {
                                    return !isBlack(m.layers.absorption()) ||
                                           m.layers.scatteringMedium;
                                  })),
      lights_(ctx.scene, lightSamplerKind(ctx.settings.getString("light-sampler")),
              triangleSampling(ctx.settings.getString("triangle-sampling"))),
      materials_(ctx.scene, ctx.camera, ctx.settings.getInt("spp")) {
  plainStage_.reserve(ctx.scene.materials.size());
  for (const Material& m : ctx.scene.materials)
    plainStage_.push_back(stageOf(ShadingMaterial::of(m, Vec3())));
}

PathEstimator::DeferStage PathEstimator::stageOf(const ShadingMaterial& sm) {
  if (Bsdf::isLambertOnly(sm)) return DeferStage::kMatte;
  if (Bsdf::isGgxMixture(sm)) return DeferStage::kGlossy;
  return Bsdf::isSmoothGlass(sm) ? DeferStage::kDelta : DeferStage::kNone;
}

void PathEstimator::reportNan(const PathState& state, const char* what, int depth) const {
  if (!debugNan_ || nanReports_.fetch_add(1) >= kMaxNanReports) return;
  std::fprintf(stderr, "debug-nan: pixel (%d, %d), depth %d: non-finite %s\n", state.pixelX,
               state.pixelY, depth, what);
}

Color PathEstimator::result(const PathState& state) {
  return state.nan ? Color(std::numeric_limits<float>::quiet_NaN()) : state.L;
}

/// Escaped: the infinite lights' radiance, weighted against their light-sampling pdfs.
void PathEstimator::escape(PathState& st) const {
  const std::vector<int>& infinite = lights_.infinite();
  if (infinite.empty()) return;
  const Vec3 dir = normalize(st.ray.d);
  for (int i : infinite) {
    const Color Le = lights_.Le(i, dir);
    if (isBlack(Le)) continue;
    float w = 1.0f;
    if (!st.specular) {
      // The choice at prev gave the environment's pmf there, if it is the light in question.
      const float pmf = i == lights_.escapeLight() && st.prevEscapePmf >= 0
                            ? st.prevEscapePmf
                            : lights_.pmf(st.prev, i);
      w = powerHeuristic(st.prevPdf, lights_.pdfChosen(i, pmf, st.prev, dir, {}, {}));
    }
    const Color c = add(st, st.beta * Le * w, "environment", st.indirectEmission, st.depth);
    if (st.paths.active()) st.paths.addFound(c, true);
  }
}

/// KHR_materials_dispersion: the path's one wavelength, drawn at a reserved dimension (no other
/// number of the sample moves: paths that never meet dispersive glass keep every bit), and its
/// spectral-to-RGB weight (materials/dispersion.h) taken into the throughput.
void PathEstimator::chooseWavelength(PathState& st, const Sampler& sampler) {
  const WavelengthSample w = sampleWavelength(sampler.reserved1D(Sampler::kWavelengthDimension));
  st.media.setWavelength(w.lambda);
  st.beta *= w.weight;
}

PathStep PathEstimator::step(PathState& st, Sampler& sampler, const Hit* found, ShadowQuery& shadow,
                             bool& wantsShadow, RayStats& stats, PrimaryHit* primary,
                             const WavefrontVertex& wave) const {
  const SurfacePoint* surface = wave.surface;
  DrawsAhead ahead = wave.ahead;
  const ShadingDeferral* deferral = wave.deferral;
  const uint32_t path = wave.path;
  wantsShadow = false;
  // KHR_materials_volume: the segment crosses the medium in effect, which absorbs.
  Color sigmaA = st.media.currentAbsorption();
  bool absorbing = !isBlack(sigmaA);
  // TRAY_materials_scattering: a medium event may end the segment first; if not, the flight's
  // weight is the segment's attenuation, and shadow rays from the hit see the extinction.
  if (st.media.scatters()) [[unlikely]] {
    PathStep next;
    if (mediumEvent(st, sampler, found, ahead, stats, next)) return next;
    sigmaA = st.media.currentExtinction();
    absorbing = false;
    if (!found) {
      escape(st);
      return PathStep::kDone;
    }
  }
  if (!found) {
    // Lost inside an open absorbing mesh: transmittance exp(-inf) = 0.
    if (!absorbing) escape(st);
    return PathStep::kDone;
  }
  const Hit& hit = *found;
  if (absorbing) {
    st.beta *= transmittance(sigmaA, hit.t * length(st.ray.d));
    if (isBlack(st.beta)) return PathStep::kDone;
  }
  Vertex v(ctx_.scene, st.ray, hit, surface);
  v.sigmaA = sigmaA;
  const SurfacePoint& s = v.s;
  v.m = &ctx_.scene.material(s.material);
  const Material& m = *v.m;
  v.wo = -normalize(st.ray.d);

  // Nested dielectrics: a surface of a medium that is not in effect is passed straight by.
  v.refractive = isRefractive(m);
  if (v.refractive && m.layers.dispersion > 0 && st.media.wavelength() == 0)
    chooseWavelength(st, sampler);
  float eta = m.ior / st.media.currentIor();
  if (v.refractive) {
    MediumStack::Interface iface = st.media.interface(s.material, m, s.frontFace);
    if (!iface.real) {
      st.media.cross(s.material, m, s.frontFace);
      if (++st.nullCrossings > kMaxNullCrossings) return PathStep::kDone;
      setSpawnRay(st.ray, s.p, s.ng, st.ray.d, s.time);
      ++stats.secondaryRays;
      return PathStep::kContinue;
    }
    eta = iface.etaT / iface.etaI;
  }
  // Textures are evaluated only at surfaces that scatter or emit (not at null interfaces).
  // Most vertices' material is its factors alone (plain): read in place, evaluated (copied)
  // only for a Bsdf (callgrind, Cornell box: evaluate's copy was 2% of the render).
  const ShadingMaterial* plain = materials_.plainFactors(hit, s);
  // Built only by evaluate(): not a std::optional, whose storage GCC 12 zeroes at its
  // declaration (a 176-byte `rep stos` per vertex, callgrind and objdump).
  Unbuilt<ShadingMaterial> late;
  ShadingMaterial& evaluated = late.value;
  const auto evaluate = [&] {
    if (plain)
      MaterialEvaluator::placeAt(*new (&evaluated) ShadingMaterial(*plain), s);
    else
      new (&evaluated) ShadingMaterial(materials_.evaluate(hit, s));
    hideOuterLayersInside(evaluated, v.refractive, s.frontFace);
  };
  if (!plain) evaluate();
  const ShadingMaterial& sm = plain ? *plain : evaluated;
  const Vec3& shadingN = plain ? s.n : evaluated.n;
  if (primary && !primary->hit) recordPrimary(*primary, st, s, shadingN, sm.baseColor);
  // KHR_materials_unlit: the base colour leaves the surface as is and nothing scatters, as
  // from an emitter that is not in the light set (docs/scene-format.md, "Unlit").
  if (sm.unlit) {
    st.paths.addFound(
        add(st, st.beta * sm.baseColor, "unlit surface", st.indirectEmission, st.depth), false);
    return PathStep::kDone;
  }

  // Emission found by BSDF sampling (or seen directly), MIS-weighted against the chance
  // that light sampling would have picked the same point.
  if (!isBlack(sm.emissive) && emitsToward(s.front, -st.ray.d, m.doubleSided)) {
    float w = 1.0f;
    int light = lights_.lightAt(hit.primitive, hit.triangle);
    if (!st.specular && light >= 0)
      w = powerHeuristic(st.prevPdf, lights_.pdf(light, st.prev, -v.wo, s.p, s.ng));
    st.paths.addFound(add(st, st.beta * sm.emissive * w, "emission", st.indirectEmission, st.depth),
                      false);
  }
  if (st.depth + 1 > maxDepth_) return PathStep::kDone;

  // Shade on the side the ray arrived from.
  v.n = s.frontFace ? shadingN : -shadingN;
  ++stats.shadedVertices;
  // A matte or glossy vertex goes to its SIMD stage before its Bsdf is built (it needs none).
  // (A plain material's stage is its factors' stage: for an inside vertex none, since both
  // stages need transmission 0.)
  if (deferral) {
    const DeferStage stage = plain ? plainStage_[size_t(s.material)] : stageOf(sm);
    if (stage == DeferStage::kMatte) {
      if (defer<false>(st, sampler, v, sm, eta, ahead, *deferral, path)) return PathStep::kDeferred;
    } else if (stage == DeferStage::kGlossy) {
      if (defer<true>(st, sampler, v, sm, eta, ahead, *deferral, path)) return PathStep::kDeferred;
    } else if (stage == DeferStage::kDelta) {
      if (deferDelta(st, sampler, v, sm, eta, ahead, *deferral, path)) return PathStep::kDeferred;
    }
  }
  if (plain) evaluate();
  const Bsdf bsdf(evaluated, v.n, eta);
  // A reflecting BSDF sees only light above n unless wo lies below it (shading normals) or a
  // clearcoat brings a normal of its own.
  // Field by field, not `= {...}`: see setSpawnRay (core/ray.h) on store-forwarding stalls.
  v.here.p = s.p;
  v.here.n = v.n;
  v.here.transmits = bsdf.transmits();
  v.here.belowMatters = belowMatters(bsdf.transmits(), v.wo, v.n, sm);
  VertexDraws draws{sampler, {ahead.first, ahead.second}};
  wantsShadow = nextEvent(st, v, bsdf, draws, shadow);
  if (wantsShadow) ++stats.shadowRays;
  return scatter(st, v, bsdf, draws, stats);
}

// nextEvent and scatter are parts of step, kept apart to be read: inlined into it (measured:
// the calls and the spilling around them cost the scalar path about 0.7% of its instructions).

/// Next-event estimation: one light sample, MIS-weighted against BSDF sampling. Returns true
/// with `shadow` set when the estimate needs its shadow ray traced.
[[gnu::always_inline]] inline bool PathEstimator::nextEvent(const PathState& st, Vertex& v,
                                                            const Bsdf& bsdf, VertexDraws& draws,
                                                            ShadowQuery& shadow) const {
  if (!bsdf.hasNonDelta() || lights_.empty()) return false;
  const SurfacePoint& s = v.s;
  // The light choice and the point on it as one 3D sample (stratified jointly by Sobol').
  const Vec3 u = draws.next3D();
  LightSample ls = v.lightChosen ? lights_.sampleChosen(v.light, v.lightPmf, v.here, {u.y, u.z})
                                 : lights_.sample(v.here, u.x, {u.y, u.z}, v.escapePmf);
  if (!ls.valid() || isBlack(ls.L)) return false;
  float bsdfPdf;
  Color f = bsdf.eval(v.wo, ls.wi, bsdfPdf) * std::fabs(dot(ls.wi, v.n));
  if (isBlack(f)) return false;
  if (ls.infinite)
    setSpawnRay(shadow.ray, s.p, s.ng, ls.wi, s.time);
  else
    setSpawnRayTo(shadow.ray, s.p, s.ng, ls.p, s.time);
  float w = ls.delta ? 1.0f : powerHeuristic(ls.pdf, bsdfPdf);
  // An unoccluded shadow ray crossed one medium: the one on its side of s.
  const Color sigma = absorbingMedia_ && v.refractive && dot(ls.wi, v.n) < 0
                          ? farSideExtinction(st.media, s.material, *v.m, s.frontFace)
                          : v.sigmaA;
  if (!isBlack(sigma)) f *= ls.infinite ? Color(0.0f) : transmittance(sigma, length(ls.p - s.p));
  shadow.contribution = neeContribution(st.beta, f, ls.L, w, ls.pdf);
  shadow.indirect = st.indirectNee;
  shadow.depth = st.depth;
  shadow.firstVertex = st.paths.atFirstVertex();
  if (st.paths.active() && shadow.firstVertex) shadow.toLight = bsdf.evalLobes(v.wo, ls.wi);
  return true;
}

/// BSDF sampling continues the path, then Russian roulette.
[[gnu::always_inline]] inline PathStep PathEstimator::scatter(PathState& st, const Vertex& v,
                                                              const Bsdf& bsdf, VertexDraws& draws,
                                                              RayStats& stats) const {
  const SurfacePoint& s = v.s;
  const Vec3 u = draws.next3D();  // the lobe choice, then the direction
  BsdfSample bs = bsdf.sample(v.wo, u.x, {u.y, u.z});
  if (!bs.valid()) return PathStep::kDone;
  st.beta = scatteredThroughput(st.beta, bs.f, bs.wi, v.n, bs.pdf);
  if (!throughputLives(st)) return PathStep::kDone;
  st.prev = v.here;
  st.prevEscapePmf = v.escapePmf;
  if (bs.transmission && v.refractive) {
    st.media.cross(s.material, *v.m, s.frontFace);
    st.etaFactor /= bs.etaScale;
  }
  if (st.paths.active())
    st.paths.scattered(!st.paths.atFirstVertex() ? LobeSplit{}
                       : bs.delta                ? LightPathSplitter::deltaLobe(bs.transmission)
                                                 : bsdf.evalLobes(v.wo, bs.wi));
  setSpawnRay(st.ray, s.p, s.ng, bs.wi, s.time);
  return nextSegment(st, draws.sampler, stats, bs.pdf, bs.delta);
}

template <bool glossy>
bool PathEstimator::defer(PathState& st, Sampler& sampler, Vertex& v, const ShadingMaterial& sm,
                          float eta, DrawsAhead ahead, const ShadingDeferral& stages,
                          uint32_t path) const {
  // What the SIMD stages repeat: a lone Lambert lobe or the metal and plastic mixture (the
  // caller's test), both draws made, a light sample drawn (nextEvent's conditions: neither
  // BSDF is all deltas), nothing for light-path AOVs, no medium to attenuate by.
  if (!stages.lightStages || !ahead.first || !ahead.second || lights_.empty() ||
      st.paths.active() || !isBlack(v.sigmaA) || (absorbingMedia_ && v.refractive))
    return false;
  // step's receiver for either BSDF: it does not transmit and has no clearcoat.
  v.here.p = v.s.p;
  v.here.n = v.n;
  v.here.transmits = false;
  v.here.belowMatters = !(dot(v.wo, v.n) > 0);
  const Vec3& u = *ahead.first;
  float pmf;
  const int light = lights_.choose(v.here, u.x, pmf, v.escapePmf);
  const bool chosen = light >= 0 && pmf > 0;
  const int32_t choice = stages.lights.choice(light);
  if (chosen && choice == kOtherLight) {  // another kind of light: the scalar code samples it
    v.lightChosen = true, v.light = light, v.lightPmf = pmf;
    return false;
  }
  ShadingLanes& m = glossy ? stages.glossy : stages.matte;  // a constant
  const size_t q = m.count++;
  const SurfacePoint& s = v.s;
  m.p[q] = s.p, m.ng[q] = s.ng, m.n[q] = v.n, m.wo[q] = v.wo;
  m.albedo[q] = sm.baseColor, m.beta[q] = st.beta;
  m.lightDraw[q] = {u.y, u.z}, m.bsdfDraw[q] = {ahead.second->y, ahead.second->z};
  m.pmf[q] = pmf;
  m.emitter[q] = chosen ? choice : int32_t(kNoLightChosen);
  if constexpr (!glossy) m.deltaSample[q] = 0;
  if constexpr (glossy) {
    m.lobeDraw[q] = ahead.second->x;
    m.metallic[q] = sm.metallic, m.roughness[q] = sm.roughness, m.eta[q] = eta;
  }
  m.path[q] = path, m.time[q] = s.time, m.belowMatters[q] = v.here.belowMatters;
  // finishDeferred makes `here` the path's prev (the stages neither read nor change this).
  st.prevEscapePmf = v.escapePmf;
  sampler.skip3D(), sampler.skip3D();  // as the two draws would have advanced it
  return true;
}

bool PathEstimator::deferDelta(PathState& st, Sampler& sampler, const Vertex& v,
                               const ShadingMaterial& sm, float eta, DrawsAhead ahead,
                               const ShadingDeferral& stages, uint32_t path) const {
  // What the delta stage repeats: scatter() for smooth glass, whose one draw (no light sample:
  // nextEvent returns before drawing) is made ahead, with nothing for light-path AOVs. Media
  // need nothing here: the segment's absorption is applied, and no shadow ray crosses one.
  if (!ahead.first || st.paths.active()) return false;
  ShadingLanes& m = stages.delta;
  const size_t q = m.count++;
  const SurfacePoint& s = v.s;
  m.p[q] = s.p, m.ng[q] = s.ng, m.n[q] = v.n, m.wo[q] = v.wo;
  m.albedo[q] = sm.baseColor, m.beta[q] = st.beta;
  m.lobeDraw[q] = ahead.first->x, m.eta[q] = eta;
  m.path[q] = path, m.time[q] = s.time;
  m.material[q] = s.material, m.frontFace[q] = s.frontFace, m.refractive[q] = v.refractive;
  st.prevEscapePmf = v.escapePmf;  // scatter's (no light was chosen here)
  sampler.skip3D();                // as the one draw would have advanced it
  return true;
}

bool PathEstimator::takeLaneSample(PathState& st, const ShadingLanes& m, size_t q, bool transmits,
                                   bool belowMatters) const {
  if (!(m.pdf[q] > 0)) return false;
  st.beta = m.nextBeta[q];
  if (!throughputLives(st)) return false;
  st.prev.p = m.p[q], st.prev.n = m.n[q];
  st.prev.transmits = transmits, st.prev.belowMatters = belowMatters;
  st.ray.o = m.rayOrigin[q], st.ray.d = m.rayDir[q];
  st.ray.tmin = 0.0f, st.ray.tmax = kInfinity;  // setSpawnRay's
  st.ray.blend = BlendRays::kStochastic, st.ray.time = m.time[q];
  return true;
}

PathStep PathEstimator::finishDelta(PathState& st, Sampler& sampler, const ShadingLanes& m,
                                    size_t q, RayStats& stats) const {
  // scatter() from the BSDF sample on: smooth glass transmits, so `here` sees both sides.
  if (!takeLaneSample(st, m, q, true, true)) return PathStep::kDone;
  if (m.transmitted[q] && m.refractive[q]) {
    const int id = m.material[q];
    st.media.cross(id, ctx_.scene.material(id), m.frontFace[q]);
    st.etaFactor /= m.etaScale[q];
  }
  return nextSegment(st, sampler, stats, m.pdf[q], true);
}

PathStep PathEstimator::finishDeferred(PathState& st, Sampler& sampler, const ShadingLanes& m,
                                       size_t q, ShadowQuery& shadow, bool& wantsShadow,
                                       RayStats& stats) const {
  wantsShadow = m.lit[q];
  if (wantsShadow) {
    shadow.ray.o = m.shadowOrigin[q], shadow.ray.d = m.shadowDir[q];
    // setSpawnRay's toward the environment, setSpawnRayTo's toward a point.
    shadow.ray.tmin = 0.0f;
    shadow.ray.tmax = m.shadowUnbounded[q] ? kInfinity : 1.0f - 1e-4f;
    shadow.ray.blend = BlendRays::kStochastic, shadow.ray.time = m.time[q];
    shadow.contribution = m.contribution[q];
    shadow.indirect = st.indirectNee;
    shadow.depth = st.depth;
    shadow.firstVertex = st.paths.atFirstVertex();
    ++stats.shadowRays;
  }
  // scatter() from the BSDF sample on (neither stage's BSDF transmits; the glossy stage's
  // sample may be a mirror's).
  if (!takeLaneSample(st, m, q, false, m.belowMatters[q])) return PathStep::kDone;
  return nextSegment(st, sampler, stats, m.pdf[q], m.deltaSample[q] != 0);
}

}  // namespace tray

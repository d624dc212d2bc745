#pragma once
// The path tracer's estimator one vertex at a time, shared by the scalar `path` integrator
// (one path traced to its end) and `path-wavefront` (every path of a batch advanced one
// segment at a time, rays traced together). Both drive the same code over the same random
// numbers, so a pixel sample gives the same radiance either way (docs/wavefront.md).
#include <algorithm>
#include <atomic>

#include "core/camera_culling.h"
#include "core/integrator.h"
#include "core/light_paths.h"
#include "integrators/glossy_batch.h"
#include "integrators/matte_batch.h"
#include "lights/light_set.h"
#include "materials/medium_stack.h"
#include "textures/shading.h"

namespace tray {

class Bsdf;

/// Everything a path carries from one vertex to the next (the locals of a recursive Li).
struct PathState {
  Ray ray;  ///< the segment to trace next
  Color L{0.0f}, beta{1.0f};
  int depth = 1;  ///< segments so far, counting the one being traced
  int nullCrossings = 0;
  bool specular = true;  ///< the last scattering was a delta lobe (or the camera): no MIS
  bool nan = false;      ///< the throughput became non-finite: the sample is discarded
  /// Firefly clamping (--clamp-indirect): a non-delta vertex precedes the current one, and
  /// one precedes the vertex the traced ray left from.
  bool indirectNee = false, indirectEmission = false;
  float prevPdf = 0;        ///< BSDF pdf of the last scattering, for MIS against light sampling
  LightSampleContext prev;  ///< the last scattering point, as light sampling saw it
  /// LightSet::pmf(prev, escapeLight()) when the light choice at prev gave it, else -1.
  float prevEscapePmf = -1;
  float etaFactor = 1;           ///< undoes the 1/eta^2 radiance scaling for Russian roulette
  int pixelX = -1, pixelY = -1;  ///< for --debug-nan reports
  /// Light-path AOVs (core/light_paths.h): each contribution also goes to its path's category
  /// when the splitter has a target.
  LightPathSplitter paths{nullptr};
  Vec3 cameraOrigin;  ///< for the primary hit's depth
  /// Last, its count first: a vertex outside every medium touches the state's first three
  /// cache lines only, not the entries' (the wavefront's steps reach a wave's paths out of
  /// order, from the L2 cache).
  MediumStack media;
  /// Scattering media (docs/subsurface.md), after the stack: touched only inside one. Events
  /// so far, the channel whose extinction draws the path's free flights (-1 until its first),
  /// and the path's pdf per channel over their mean (integrators/free_flight.h).
  int mediumEvents = 0;
  int8_t heroChannel = -1;
  Color channelRatios{1.0f};
  /// The members' own initializers only. Written out, not defaulted: value-initialising a
  /// class whose default constructor is implicit zeroes all of it first, and the wavefront's
  /// emplace_back() did so for every camera path (a 384-byte `rep stos`; the media's entries
  /// are read only below their count).
  PathState() {}  // NOLINT(modernize-use-equals-default)
  /// A path starting with the camera ray `ray` of pixel (x, y); its light-path split goes to
  /// `lightPaths` when not null.
  static PathState camera(const Ray& ray, int x, int y, LightPathRadiance* lightPaths) {
    PathState s;
    s.beginCamera(ray, x, y, lightPaths);
    return s;
  }
  /// The same on a freshly default-constructed state, in place (the wavefront's queue slot:
  /// copying a just-built state in costs a store-forwarding stall, core/ray.h).
  void beginCamera(const Ray& cameraRay, int x, int y, LightPathRadiance* lightPaths) {
    ray = cameraRay;
    beginCamera(x, y, lightPaths);
  }
  /// The same once the caller has written the camera ray into `ray` (field by field, as the
  /// wavefront's camera-ray kernel does: no Ray temporary to copy).
  void beginCamera(int x, int y, LightPathRadiance* lightPaths) {
    cameraOrigin = ray.o, pixelX = x, pixelY = y;
    paths = LightPathSplitter(lightPaths);
  }
};

/// A next-event estimate waiting for its shadow ray: added to the path's radiance if the ray
/// is not occluded. Deferring the test changes no random number and no order of additions.
struct ShadowQuery {
  Ray ray;
  Color contribution;
  bool indirect = false;  ///< clamped by --clamp-indirect
  int depth = 0;          ///< for --debug-nan reports
  /// Light-path AOVs: drawn at the path's first vertex, and then (only with a splitter target)
  /// the BSDF's split toward the light.
  bool firstVertex = false;
  LobeSplit toLight;
};

/// A vertex's two 3D draws made ahead in SIMD (integrators/sampler_batch.h), or none (null): the
/// light sample's and then the BSDF sample's come from here in that order, each skipping the
/// sampler past it; a vertex that draws only one (no light sample) takes `first` for its BSDF
/// sample.
struct DrawsAhead {
  const Vec3* first = nullptr;
  const Vec3* second = nullptr;
};

/// What one vertex did to its path.
enum class PathStep : uint8_t {
  kContinue,  ///< state.ray is the next segment
  kDone,      ///< the path ended (escaped, absorbed, roulette, max depth, NaN)
  kDeferred,  ///< the vertex waits in a SIMD stage's lanes: finishDeferred completes it
};

/// Where step() may leave a vertex for a SIMD shading stage: a matte one (a lone Lambert lobe,
/// integrators/matte_batch.h), a glossy one (the metal and plastic mixture,
/// integrators/glossy_batch.h) or a delta one (smooth glass, integrators/delta_batch.h), each
/// in its own lanes.
struct ShadingDeferral {
  const MatteBatch& lights;  ///< which light choices the stages sample (matte and glossy)
  ShadingLanes& matte;
  ShadingLanes& glossy;
  ShadingLanes& delta;
  /// The matte and glossy stages run (MatteBatch::useful: they sample some light); the delta
  /// stage, which samples none, always does.
  bool lightStages;
};

/// What the wavefront made ahead for one vertex of its queue; the scalar driver makes none (the
/// same numbers either way).
struct WavefrontVertex {
  /// Scene::surface(state.ray, hit), computed for the queue in SIMD
  /// (integrators/surface_batch.h); null: step computes it.
  const SurfacePoint* surface = nullptr;
  /// The sampler's next two 3D draws, made for the queue in SIMD.
  DrawsAhead ahead;
  /// Where a vertex may wait for a SIMD shading stage: one with a lone Lambert lobe, or with
  /// the metal and plastic mixture (and both draws made ahead, no light-path split, no
  /// absorbing medium) whose light choice is one the stages sample (an emissive triangle or
  /// the constant environment) or none is chosen, is queued in its stage's lanes with its
  /// inputs as `path` (kDeferred, the sampler past both draws). Null: none.
  const ShadingDeferral* deferral = nullptr;
  uint32_t path = 0;
};
/// Unidirectional path tracing with next-event estimation and MIS (Veach 1997, ch. 9), written
/// as a step per vertex. Thread-safe: all per-path data lives in PathState.
class PathEstimator {
 public:
  explicit PathEstimator(const RenderContext& ctx);
  int maxDepth() const { return maxDepth_; }
  /// Processes the result of tracing state.ray (`hit`: its closest hit, null when it escaped):
  /// emission, NEE (sets `shadow` and returns true in `wantsShadow` when a shadow ray must be
  /// tested), BSDF sampling and Russian roulette. Fills `primary` at the first surface if not
  /// null. `wave`: what the wavefront made ahead for this vertex (none for the scalar driver).
  PathStep step(PathState& state, Sampler& sampler, const Hit* hit, ShadowQuery& shadow,
                bool& wantsShadow, RayStats& stats, PrimaryHit* primary,
                const WavefrontVertex& wave = {}) const;
  /// The rest of a deferred vertex once its stage's compute has run: entry q of `lanes`
  /// becomes the shadow query (wantsShadow) and the next segment, as step() would have made
  /// them, then Russian roulette.
  PathStep finishDeferred(PathState& state, Sampler& sampler, const ShadingLanes& lanes, size_t q,
                          ShadowQuery& shadow, bool& wantsShadow, RayStats& stats) const;
  /// The same for entry q of the delta stage's lanes (no shadow ray: every lobe is a delta).
  PathStep finishDelta(PathState& state, Sampler& sampler, const ShadingLanes& lanes, size_t q,
                       RayStats& stats) const;
  const LightSet& lights() const { return lights_; }
  /// MaterialEvaluator::prefetchTextures, for a queue's vertices before they are shaded.
  bool textured() const { return materials_.textured(); }
  void prefetchTextures(const SurfacePoint& s) const { materials_.prefetchTextures(s); }
  /// Adds a next-event estimate whose shadow ray was traced.
  void resolveShadow(PathState& state, const ShadowQuery& shadow, bool occluded) const {
    if (occluded) return;
    const Color c = add(state, shadow.contribution, "light sample", shadow.indirect, shadow.depth);
    if (state.paths.active()) state.paths.addLightSample(c, shadow.toLight, shadow.firstVertex);
  }
  /// The sample's radiance once the path is done (NaN when the throughput became non-finite:
  /// counted and discarded upstream).
  static Color result(const PathState& state);
  /// One path traced to its end, one ray at a time: the scalar driver (`path-scalar`), and
  /// what the wavefront's Li does too (a lone path has nothing to batch with; adaptive calls
  /// Li sample by sample). (x, y): the pixel, for --debug-nan reports (-1 when unknown).
  Color tracePath(const Accelerator& accel, const Ray& cameraRay, Sampler& sampler, RayStats& stats,
                  PrimaryHit* primary, int x, int y) const {
    if (maxDepth_ == 0) return Color(0.0f);
    PathState state = PathState::camera(cameraRay, x, y, primary ? primary->lightPaths : nullptr);
    ShadowQuery shadow;  // step() sets what resolveShadow reads: not re-initialised per vertex
    for (bool fromCamera = true;; fromCamera = false) {
      Hit hit;
      // The camera's ray passes single-sided back faces (core/camera_culling.h).
      const bool found = fromCamera ? intersectCameraRay(accel, ctx_.scene, state.ray, hit)
                                    : accel.intersect(state.ray, hit);
      bool wantsShadow;
      const PathStep next =
          step(state, sampler, found ? &hit : nullptr, shadow, wantsShadow, stats, primary);
      if (wantsShadow) resolveShadow(state, shadow, accel.occluded(shadow.ray));
      if (next == PathStep::kDone) break;
    }
    return result(state);
  }

 private:
  struct Vertex;
  struct VertexDraws;
  bool nextEvent(const PathState& st, Vertex& v, const Bsdf& bsdf, VertexDraws& draws,
                 ShadowQuery& shadow) const;
  PathStep scatter(PathState& st, const Vertex& v, const Bsdf& bsdf, VertexDraws& draws,
                   RayStats& stats) const;
  /// Queues a vertex whose BSDF would be a lone Lambert lobe (glossy false) or the metal and
  /// plastic mixture (glossy true) of `sm` in the stage's lanes when the rest qualifies (see
  /// step), setting v.here; false: step goes on. A template: the matte vertices' call has no
  /// branch on the stage (callgrind, Cornell box: -0.2% of the render).
  template <bool glossy>
  bool defer(PathState& st, Sampler& sampler, Vertex& v, const ShadingMaterial& sm, float eta,
             DrawsAhead ahead, const ShadingDeferral& stages, uint32_t path) const;
  /// Queues a smooth glass vertex (Bsdf::isSmoothGlass) in the delta stage's lanes when the
  /// rest qualifies (its one draw made ahead, no light-path split); false: step goes on.
  bool deferDelta(PathState& st, Sampler& sampler, const Vertex& v, const ShadingMaterial& sm,
                  float eta, DrawsAhead ahead, const ShadingDeferral& stages, uint32_t path) const;
  /// scatter()'s tail for the sample a SIMD stage made for entry q of `m`: the throughput after
  /// it, `here` (the lanes' p and n, these receiver flags) as the path's prev, and the next ray.
  /// False: the path ends (no sample, or a throughput that does not live on).
  bool takeLaneSample(PathState& st, const ShadingLanes& m, size_t q, bool transmits,
                      bool belowMatters) const;
  /// After a BSDF sample set st.beta (scatter, or a SIMD stage for finishDeferred): false, the
  /// path done, when the throughput is not finite (counted and discarded upstream) or black.
  [[gnu::always_inline]] bool throughputLives(PathState& st) const {
    if (!isFinite(st.beta)) {
      reportNan(st, "path throughput", st.depth);
      st.nan = true;
      return false;
    }
    return !isBlack(st.beta);
  }
  /// What every BSDF sample records in the path, whoever made it (the caller has set st.prev
  /// and st.ray): the MIS state the next hit reads, one more segment, then Russian roulette.
  [[gnu::always_inline]] PathStep nextSegment(PathState& st, Sampler& sampler, RayStats& stats,
                                              float pdf, bool delta) const {
    st.specular = delta;
    st.indirectEmission = st.indirectNee;
    st.indirectNee = st.indirectNee || !delta;
    st.prevPdf = pdf;
    ++stats.secondaryRays;
    ++st.depth;
    return roulette(st, sampler);
  }
  /// Russian roulette after a scattering (Arvo & Kirk 1990), after the first --rr-depth
  /// segments (docs/bench/roulette-2026-12-07.md measures both options).
  PathStep roulette(PathState& st, Sampler& sampler) const {
    if (st.depth > rouletteDepth_ && !survivesRoulette(st, sampler)) return PathStep::kDone;
    return PathStep::kContinue;
  }
  /// One roulette draw: false ends the path; a survivor's throughput is divided by its
  /// probability of surviving, which keeps the estimate unbiased (roulette() and a medium's
  /// events, integrators/path_medium.cpp).
  bool survivesRoulette(PathState& st, Sampler& sampler) const {
    const float q = survival(maxComponent(st.beta) * st.etaFactor);
    if (!(sampler.next1D() < q)) return false;
    st.beta /= q;
    return true;
  }
  /// The probability that a path of throughput `t` (its largest component, radiance scaling
  /// by refraction undone) goes on: by default (--rr-survival sqrt) Cycles' min(1, sqrt(t))
  /// (integrator/path_state.h, path_state_continuation_probability) capped at Mitsuba's 0.95,
  /// which keeps more of the dim paths whose survivors would otherwise weigh 1/t each; or
  /// Mitsuba's min(0.95, t) (--rr-survival throughput).
  float survival(float t) const { return std::min(sqrtSurvival_ ? std::sqrt(t) : t, 0.95f); }
  /// Adds `c` to the path's radiance (clamped when indirect) and returns what was added.
  /// Firefly clamping (--clamp-indirect): light that reached the camera path after scattering
  /// off a diffuse or glossy vertex earlier than the one gathering it (caustics,
  /// interreflection) is "indirect". Each such contribution is scaled down, keeping its hue, so
  /// that its largest component is at most clampIndirect_: biased (energy is lost) but bounded
  /// per sample, the "clamp indirect" of Cycles and Arnold. Direct light at the first non-delta
  /// vertex, and emitters seen directly or through mirrors and glass, are never clamped. Here,
  /// not in the .cpp, so that the drivers' resolveShadow inlines it.
  Color add(PathState& state, Color c, const char* what, bool indirect, int depth) const {
    if (!isFinite(c)) reportNan(state, what, depth);
    if (clampIndirect_ > 0 && indirect) {  // the constant first: a predictable branch
      const float peak = maxComponent(c);
      if (peak > clampIndirect_) c *= clampIndirect_ / peak;
    }
    state.L += c;
    return c;
  }
  void escape(PathState& state) const;
  /// TRAY_materials_scattering (integrators/path_medium.cpp, docs/subsurface.md): the free
  /// flight of st.ray's segment through the scattering medium in effect. True: a medium event
  /// came before `hit` (null: the segment escapes) and `next` is what became of the path (its
  /// next segment set); false: the segment reaches `hit` (or escapes), the throughput weighted
  /// for it, and `ahead` holds the draws made ahead that are left for the vertex there.
  bool mediumEvent(PathState& st, Sampler& sampler, const Hit* hit, DrawsAhead& ahead,
                   RayStats& stats, PathStep& next) const;
  void recordPrimary(PrimaryHit& primary, const PathState& st, const SurfacePoint& s,
                     const Vec3& shadingN, const Color& albedo) const;
  /// Which SIMD stage a vertex of material `sm` may go to (step's test, before its lights).
  enum class DeferStage : uint8_t { kNone, kMatte, kGlossy, kDelta };
  static DeferStage stageOf(const ShadingMaterial& sm);
  void reportNan(const PathState& state, const char* what, int depth) const;
  /// KHR_materials_dispersion: picks the path's wavelength at its first dispersive surface.
  static void chooseWavelength(PathState& st, const Sampler& sampler);
  static constexpr int kMaxNanReports = 10;
  /// A walk in a scattering medium plays Russian roulette after this many events too.
  static constexpr int kRouletteMediumEvents = 5;
  /// A random walk in a scattering medium ends after this many events (Cycles stops its
  /// random-walk subsurface at 256): a bias only for media far denser than their size.
  static constexpr int kMaxMediumEvents = 1024;
  const RenderContext& ctx_;
  int maxDepth_;
  int rouletteDepth_;  ///< --rr-depth
  bool sqrtSurvival_;  ///< --rr-survival sqrt
  float clampIndirect_;
  bool debugNan_;
  bool absorbingMedia_;  ///< some material absorbs (KHR_materials_volume): NEE looks it up
  LightSet lights_;
  MaterialEvaluator materials_;
  /// Per material: stageOf its factors, for the vertices where they are all of it (plain).
  std::vector<DeferStage> plainStage_;
  mutable std::atomic<int> nanReports_{0};
};

}  // namespace tray

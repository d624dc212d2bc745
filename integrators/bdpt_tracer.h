#pragma once
// Bidirectional path tracing's estimator (Veach 1997 ch. 10; the structure of pbrt-v3 16.3):
// a camera subpath and a light subpath, every connection of a prefix of one to a prefix of the
// other, each weighted by the power heuristic over all strategies that make the same path.
// Used by the `bdpt` integrator (integrators/bdpt.cpp): its pixel pass takes the strategies
// with t >= 2 camera vertices, its light-tracing pass those with t = 1.
#include <vector>

#include "core/camera_importance.h"
#include "core/integrator.h"
#include "integrators/bdpt_vertex.h"
#include "lights/emission_sampler.h"
#include "lights/light_set.h"
#include "materials/medium_stack.h"
#include "textures/shading.h"

namespace tray {

/// Which strategies an estimate takes (--bdpt-strategy): all of them MIS-weighted, or one
/// family unweighted (a debugging check: each family alone converges to the same image on
/// scenes it can sample, Veach 1997 §10.3.5). Emitters seen directly (s = 0, t = 2, the one
/// strategy for one-segment paths) are in every family.
enum class BdptStrategies : uint8_t {
  kAll,
  kS0,  ///< s = 0: the camera subpath finds an emitter (no next-event estimation)
  kS1,  ///< s = 1: next-event estimation from every camera vertex
  kT1,  ///< t = 1: light tracing, every light vertex connected to the camera
};

/// A light-tracing contribution: radiance for the pixel at `raster`, from one light path.
struct Splat {
  Vec2 raster;
  Color L;
};

class BdptTracer {
 public:
  /// Throws tray::Error for what it cannot render (a thin lens, motion blur).
  explicit BdptTracer(const RenderContext& ctx);
  int maxDepth() const { return maxDepth_; }
  /// Strategies with t >= 2 for one camera ray: the camera subpath from `ray`, a light
  /// subpath, every connection; fills `primary` at the first surface when not null.
  Color cameraEstimate(const Ray& ray, Sampler& sampler, RayStats& stats,
                       PrimaryHit* primary) const;
  /// Strategies with t = 1 for one light subpath drawn from `sampler`: appends its splats.
  void lightEstimate(Sampler& sampler, RayStats& stats, std::vector<Splat>& out) const;

  /// The power-heuristic weight of strategy (s, t) for the path light[0..s) + camera[t..0),
  /// the connection's vertices already holding their connection densities (connect() sets
  /// them; tests call it on paths of their own). Exposed for the tests' weight-sum check.
  float misWeight(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int s,
                  int t) const;
  /// Sets the densities that connecting light[s-1] to camera[t-1] gives the vertices around
  /// the connection (pdfRev of camera[t-1], camera[t-2], light[s-1], light[s-2]), as
  /// misWeight reads them. `sampled`: the s = 1 light vertex, when s == 1.
  void setConnectionPdfs(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int s,
                         int t) const;
  /// Camera and light subpaths (tests): from `ray` and from an emission sample.
  void cameraSubpath(const Ray& ray, Sampler& sampler, RayStats& stats, PrimaryHit* primary,
                     std::vector<BdptVertex>& out) const;
  void lightSubpath(Sampler& sampler, RayStats& stats, std::vector<BdptVertex>& out) const;
  /// Solid-angle density of sampling direction `to` at surface v given the other direction
  /// `from` (both leaving v).
  float pdfDirAt(const BdptVertex& v, const Vec3& from, const Vec3& to) const;
  /// The emission densities of light vertex (or emitter hit) v toward `to`: of v's origin as
  /// a light subpath starts (choice x position; direction for lights at infinity) and of
  /// `to` as the area density the emitted ray reaches it with.
  float pdfLightOrigin(const BdptVertex& v, const Vec3& towardTo) const;
  float pdfLightTo(const BdptVertex& v, const BdptVertex& to) const;
  /// Weight for strategy (s, t) under the chosen strategies (1 or 0 for a lone family); the
  /// subpaths' densities are as the walks left them, the connection's are set here.
  float weight(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int s, int t) const;
  const CameraImportance& camera() const { return camera_; }
  const LightSet& lightSet() const { return lights_; }
  void setStrategies(BdptStrategies s) { strategies_ = s; }

 private:
  enum class Mode : uint8_t { kRadiance, kImportance };
  /// Extends `path` from its last vertex along `ray` (solid-angle density pdfDir of its
  /// direction; after the camera, CameraImportance::pdfFirst) until maxVertices, absorption or a
  /// failed sample; beta the throughput.
  void walk(Ray ray, Color beta, float pdfDir, Sampler& sampler, RayStats& stats, Mode mode,
            size_t maxVertices, MediumStack media, PrimaryHit* primary,
            std::vector<BdptVertex>& path) const;
  /// A surface vertex at the hit of `ray`; false: a null interface (the walk goes through).
  bool surfaceVertex(const Ray& ray, const Hit& hit, MediumStack& media, BdptVertex& v) const;
  /// The contributions (unweighted) of the strategies.
  Color connectS0(std::vector<BdptVertex>& camera, int t) const;
  Color connectS1(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int t,
                  Sampler& sampler, RayStats& stats) const;
  Color connectInner(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int s, int t,
                     RayStats& stats) const;
  bool connectToCamera(std::vector<BdptVertex>& light, std::vector<BdptVertex>& camera, int s,
                       RayStats& stats, Splat& out) const;
  /// Whether the segment between two points is unoccluded (alpha as the accelerator says).
  bool visible(const BdptVertex& a, const BdptVertex& b) const;

  const RenderContext& ctx_;
  int maxDepth_;
  BdptStrategies strategies_ = BdptStrategies::kAll;
  CameraImportance camera_;
  LightSet lights_;
  EmissionSampler emission_;
  MaterialEvaluator materials_;
};

}  // namespace tray

#pragma once
// Where a path traced from the camera or from a light meets a surface, for the estimators that
// walk paths vertex by vertex outside the path tracer (photon mapping, integrators/sppm.h):
// the surface point, its material with textures evaluated, nested dielectrics' false
// interfaces passed straight through, and the shading frame on the side the ray arrived from.
// The same rules as PathEstimator::step (integrators/path_estimator.cpp).
#include "core/integrator.h"
#include "materials/bsdf.h"
#include "materials/medium_stack.h"
#include "textures/shading.h"

namespace tray {

/// One surface vertex, ready for a Bsdf(sm, n, eta).
struct SurfaceVertex {
  SurfacePoint s;
  const Material* m = nullptr;
  ShadingMaterial sm;
  Vec3 n;   ///< shading normal on the side the ray arrived from
  Vec3 wo;  ///< unit, towards where the ray came from
  float eta = 1;
  bool refractive = false;  ///< the material may transmit (its surface bounds a medium)
  Bsdf bsdf() const { return Bsdf(sm, n, eta); }
};

/// What the ray met.
enum class VertexKind : uint8_t {
  kPassed,   ///< a false interface of nested dielectrics: `ray` continues past it
  kGaveUp,   ///< too many false interfaces in a row: the path ends
  kSurface,  ///< a surface that scatters, emits or is unlit: `v` is filled
};

class SurfaceVertices {
 public:
  /// `samplesPerPixel` narrows the texture footprint as the path tracer's (MaterialEvaluator).
  SurfaceVertices(const RenderContext& ctx, int samplesPerPixel);
  /// The vertex where `ray` hit (`hit`), inside `media`. A false interface crosses it in
  /// `media`, moves `ray` past it and counts it in `nullCrossings` (kPassed).
  VertexKind at(Ray& ray, const Hit& hit, MediumStack& media, int& nullCrossings,
                SurfaceVertex& v) const;
  /// Crosses the vertex's surface in `media` after a sampled transmission.
  static void transmit(const SurfaceVertex& v, MediumStack& media) {
    if (v.refractive) media.cross(v.s.material, *v.m, v.s.frontFace);
  }

 private:
  const Scene& scene_;
  MaterialEvaluator materials_;
};

}  // namespace tray

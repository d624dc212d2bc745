#pragma once
// Glossy vertices in SIMD (Highway, dynamic dispatch): the second half of PathEstimator::step
// for every queued vertex whose BSDF is glTF's metal and plastic mixture (GGX reflection with
// Schlick's metal Fresnel, the plastic's dielectric GGX coat, Lambert below it; Bsdf::
// isGgxMixture) and whose light choice fell on an emissive triangle, the constant environment
// or no light: every vertex of the bench spheres and most of the helmets'. The light sample,
// the mixture's value and pdf toward it and the MIS weight, the shadow ray, the mixture's
// sample (the lobe choice, GGX visible normals or the cosine lobe), its value and pdf, and
// the next ray are computed for a vector of vertices at once, bit for bit the scalar step's
// (docs/wavefront.md, "Glossy shading in SIMD").
#include "integrators/matte_batch.h"
#include "integrators/shading_lanes.h"

namespace tray {

/// The SIMD stage for metal and plastic vertices: the lights it samples, and their table, are
/// the matte stage's (MatteBatch::choice).
class GlossyBatch {
 public:
  /// Worth deferring vertices to when the matte stage is (MatteBatch::useful).
  explicit GlossyBatch(const MatteBatch& lights);
  /// Computes the outputs of lanes.count vertices (their inputs padded: padInputs).
  void compute(ShadingLanes& lanes) const;

 private:
  const MatteBatch& lights_;
};

}  // namespace tray

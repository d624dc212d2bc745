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
#include <cstdint>

#include "integrators/matte_batch.h"
#include "integrators/shading_lanes.h"
#include "lights/light_set.h"

namespace tray {

/// The SIMD stage for metal and plastic vertices. Gathers emissive triangles from the matte
/// stage's table; the constant environment's radiance is one colour.
class GlossyBatch {
 public:
  GlossyBatch(const LightSet& lights, const MatteBatch& emitters);
  /// A SIMD target and some light: worth deferring vertices to.
  bool useful() const { return useful_; }
  /// Light `index` as the lanes name it: a triangle's row of the table, kConstantEnvironment,
  /// or kOtherLight when the stage does not sample it (the scalar code does).
  int32_t choice(int index) const {
    if (index >= 0 && index == environment_) return kConstantEnvironment;
    const int32_t row = emitters_.row(index);
    return row >= 0 ? row : kOtherLight;
  }
  static constexpr int32_t kOtherLight = -3;
  /// Computes the outputs of lanes.count vertices (their inputs padded: padInputs).
  void compute(ShadingLanes& lanes) const;

 private:
  const MatteBatch& emitters_;
  int environment_ = -1;  ///< the constant environment's light index, or -1
  Color environmentLe_{0.0f};
  bool useful_ = false;
};

}  // namespace tray

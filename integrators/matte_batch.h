#pragma once
// Matte vertices in SIMD (Highway, dynamic dispatch): the second half of PathEstimator::step
// for every queued vertex whose BSDF is a lone Lambert lobe and whose light choice fell on an
// emissive triangle, the constant environment or no light: every vertex of the Cornell box
// and of the white furnace. The light
// sample, its Lambert term and MIS weight, the shadow ray, the cosine-weighted BSDF sample
// and the next ray are computed for a vector of vertices at once, bit for bit the scalar
// step's (docs/wavefront.md, "Matte shading in SIMD").
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "integrators/shading_lanes.h"
#include "lights/light_set.h"

namespace tray {

/// What the stages' light samples read: the emissive triangles' and punctual lights' tables
/// (MatteBatch::Column, PunctualColumn), how the triangles are sampled and the constant
/// environment's radiance.
struct EmitterTables {
  const float* triangles;
  const float* punctual;
  Color environmentLe;
  TriangleSampling triangleSampling;
};

/// The SIMD stage: the scene's emissive triangles as a table the kernel gathers from, and the
/// constant environment's radiance.
class MatteBatch {
 public:
  explicit MatteBatch(const LightSet& lights);
  /// A SIMD target and a light the stage samples (an emissive triangle, a punctual light or
  /// the constant environment): worth deferring vertices to.
  bool useful() const { return useful_; }
  /// Light `index` as the lanes name it: a triangle's row of the table, kConstantEnvironment,
  /// a punctual light's code (kFirstPunctual - row), or kOtherLight when the stages do not
  /// sample it (the scalar code does: an image environment, an analytic shape; also for -1).
  int32_t choice(int index) const {
    return index >= 0 && size_t(index) < choices_.size() ? choices_[size_t(index)]
                                                         : int32_t(kOtherLight);
  }
  /// Computes the outputs of lanes.count vertices (their inputs padded: padInputs).
  void compute(ShadingLanes& lanes) const;
  /// The emitter and punctual tables and the environment's radiance, as the stages' light
  /// samples read them (the glossy stage gathers from them too).
  EmitterTables tables() const {
    return {table_.data(), punctual_.data(), environmentLe_, triangleSampling_};
  }

  /// Floats per row: vertex 0, the two edges, the unit front normal, the area, the radiance
  /// and whether both faces emit (1 or 0). A rectangle (AreaLight::isRectangle: corner and
  /// edges) has its area negated: one table, no column more to gather.
  // clang-format off
  enum Column : uint8_t {
    kP0x, kP0y, kP0z, kE1x, kE1y, kE1z, kE2x, kE2y, kE2z, kNx, kNy, kNz,
    kArea, kLeR, kLeG, kLeB, kDoubleSided, kColumnCount
  };
  /// Floats per row of the punctual table: whether the light is directional and whether a spot
  /// (1 or 0), its position, the direction its light travels, its intensity, and a spot's cone
  /// cosines (PunctualLightOf).
  enum PunctualColumn : uint8_t {
    kDirectional, kSpot, kPx, kPy, kPz, kDx, kDy, kDz, kIr, kIg, kIb, kCosOuter, kCosInner,
    kPunctualColumnCount
  };
  // clang-format on

 private:
  std::vector<float> table_;      ///< kColumnCount floats per row
  std::vector<float> punctual_;   ///< kPunctualColumnCount floats per row
  std::vector<int32_t> choices_;  ///< per light index
  Color environmentLe_{0.0f};
  TriangleSampling triangleSampling_ = TriangleSampling::kAuto;
  bool useful_ = false;
};

}  // namespace tray

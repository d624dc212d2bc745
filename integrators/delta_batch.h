#pragma once
// Smooth glass vertices in SIMD (Highway, dynamic dispatch): the second half of
// PathEstimator::step for every queued vertex whose BSDF is smooth glass alone (two delta
// lobes, Bsdf::isSmoothGlass): the glass sphere of the helmets and the glass of most glTF
// assets. Every lobe is a delta, so there is no light sample: the lobe choice by exact Fresnel,
// the mirrored or refracted direction, the throughput and the next ray are computed for a
// vector of vertices at once, bit for bit the scalar step's (docs/wavefront.md, "Delta
// vertices in SIMD").
#include "integrators/shading_lanes.h"

namespace tray {

/// The SIMD stage for delta vertices. It samples no light: it needs only a SIMD target.
class DeltaBatch {
 public:
  DeltaBatch();
  /// A SIMD target: worth deferring vertices to.
  bool useful() const { return useful_; }
  /// Computes the outputs of lanes.count vertices (their inputs padded: padInputs).
  void compute(ShadingLanes& lanes) const;

 private:
  bool useful_;
};

}  // namespace tray

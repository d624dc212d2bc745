#pragma once
// The vertices one bounce leaves to a SIMD shading stage (integrators/matte_batch.h,
// integrators/glossy_batch.h, integrators/delta_batch.h): their inputs and results, one array
// per field.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace tray {

/// Light choices as the stages name them (MatteBatch::choice), in ShadingLanes::emitter beside
/// a triangle's row of the emitter table (>= 0).
enum EmitterChoice : int32_t {
  kNoLightChosen = -1,
  kConstantEnvironment = -2,  ///< the scene's constant environment
  kOtherLight = -3,           ///< a light the stages do not sample (never in the lanes)
  kFirstPunctual = -4,        ///< row j of the punctual table is kFirstPunctual - j
};

/// The deferred vertices of one bounce, one array per field (Vec3 fields as arrays of Vec3:
/// step and finishDeferred copy whole vectors, the kernels load and store them interleaved),
/// each with room for whole vectors (core/simd_lanes.h). Filled by PathEstimator::step,
/// computed by a stage's compute, read back by PathEstimator::finishDeferred. Reused from one
/// bounce to the next: no allocation once grown.
struct ShadingLanes {
  size_t count = 0;
  // Inputs: the surface point and its geometric normal; the shading normal on the side the
  // ray arrived from; towards where it came from; the base colour; the path's throughput; the
  // light sample's point draw and the BSDF sample's direction draw (the last two numbers of
  // each 3D draw); the light choice's probability and what was chosen (a row of the emitter
  // table, or an EmitterChoice).
  std::vector<Vec3> p, ng, n, wo, albedo, beta;
  std::vector<Vec2> lightDraw, bsdfDraw;
  std::vector<float> pmf;
  std::vector<int32_t> emitter;
  // The glossy stage's inputs besides: the lobe choice (the BSDF draw's first number), the
  // material's metallic and roughness and the relative IOR across the surface. The delta
  // stage's inputs are p, ng, n, wo, albedo (the glass tint), beta, lobeDraw and eta.
  std::vector<float> lobeDraw, metallic, roughness, eta;
  // Outputs: the shadow ray's origin and direction and the estimate it carries (when `lit`);
  // the next ray's origin and direction, the throughput after it and the BSDF sample's pdf
  // (no sample unless > 0).
  std::vector<Vec3> shadowOrigin, shadowDir, contribution, rayOrigin, rayDir, nextBeta;
  std::vector<float> pdf;
  std::vector<int32_t> lit;  ///< all bits set or none
  /// Whether the shadow ray is unbounded (toward the environment or a directional light; all
  /// bits set or none): finishDeferred's tmax.
  std::vector<int32_t> shadowUnbounded;
  /// The glossy stage's besides: whether the BSDF sample was a mirror's (a delta lobe; all bits
  /// set or none). The matte stage's are never (PathEstimator::defer clears them).
  std::vector<int32_t> deltaSample;
  // The delta stage's outputs besides: whether the sample refracted (all bits set or none) and
  // its etaScale (BsdfSample::etaScale).
  std::vector<int32_t> transmitted;
  std::vector<float> etaScale;
  // Not for the kernels: the wave's path the vertex belongs to, its rays' shutter time and
  // LightSampleContext::belowMatters there; for the delta stage, the surface's material, its
  // side (SurfacePoint::frontFace) and whether it bounds a medium (a refraction crosses it).
  std::vector<uint32_t> path;
  std::vector<float> time;
  std::vector<uint8_t> belowMatters;
  std::vector<int32_t> material;
  std::vector<uint8_t> frontFace, refractive;

  /// Empties the lanes and makes room for `size` vertices (never shrinks).
  void reset(size_t size);
  /// Zeroes the inputs past `count` up to whole vectors: a kernel's last vector reads them
  /// (defined values: no gather from a stray row, nothing uninitialised for Valgrind).
  void padInputs();
};

}  // namespace tray

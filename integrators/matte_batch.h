#pragma once
// Matte vertices in SIMD (Highway, dynamic dispatch): the second half of PathEstimator::step
// for every queued vertex whose BSDF is a lone Lambert lobe and whose light choice fell on an
// emissive triangle (or on no light), which is every vertex of the Cornell box. The light
// sample, its Lambert term and MIS weight, the shadow ray, the cosine-weighted BSDF sample
// and the next ray are computed for a vector of vertices at once, bit for bit the scalar
// step's (docs/wavefront.md, "Matte shading in SIMD").
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "lights/light_set.h"

namespace tray {

/// The deferred vertices of one bounce, one array per field (Vec3 fields as arrays of Vec3:
/// step and finishMatte copy whole vectors, the kernel loads and stores them interleaved),
/// each with room for whole vectors (core/simd_lanes.h). Filled by PathEstimator::step,
/// computed by MatteBatch::compute, read back by PathEstimator::finishMatte. Reused from one
/// bounce to the next: no allocation once grown.
struct MatteLanes {
  size_t count = 0;
  // Inputs: the surface point and its geometric normal; the shading normal on the side the
  // ray arrived from; towards where it came from; the albedo; the path's throughput; the
  // light sample's point draw and the BSDF sample's direction draw (the last two numbers of
  // each 3D draw); the light choice's probability and the chosen triangle's row of
  // MatteBatch's table (-1: no light chosen).
  std::vector<Vec3> p, ng, n, wo, albedo, beta;
  std::vector<Vec2> lightDraw, bsdfDraw;
  std::vector<float> pmf;
  std::vector<int32_t> emitter;
  // Outputs: the shadow ray's origin and direction and the estimate it carries (when `lit`);
  // the next ray's origin and direction, the throughput after it and the BSDF sample's pdf
  // (no sample unless > 0).
  std::vector<Vec3> shadowOrigin, shadowDir, contribution, rayOrigin, rayDir, nextBeta;
  std::vector<float> pdf;
  std::vector<int32_t> lit;  ///< all bits set or none
  // Not for the kernel: the wave's path the vertex belongs to, its rays' shutter time and
  // LightSampleContext::belowMatters there.
  std::vector<uint32_t> path;
  std::vector<float> time;
  std::vector<uint8_t> belowMatters;

  /// Empties the lanes and makes room for `size` vertices (never shrinks).
  void reset(size_t size);
  /// Zeroes the inputs past `count` up to whole vectors: the kernel's last vector reads them
  /// (defined values: no gather from a stray row, nothing uninitialised for Valgrind).
  void padInputs();
};

/// The SIMD stage: the scene's emissive triangles as a table the kernel gathers from.
class MatteBatch {
 public:
  explicit MatteBatch(const LightSet& lights);
  /// A SIMD target and at least one emissive triangle: worth deferring vertices to.
  bool useful() const { return useful_; }
  /// Light `index`'s row of the table, or -1 when it is not an emissive triangle.
  int32_t row(int index) const {
    return index >= 0 && size_t(index) < rows_.size() ? rows_[size_t(index)] : -1;
  }
  /// Computes the outputs of lanes.count vertices (their inputs padded: padInputs).
  void compute(MatteLanes& lanes) const;

  /// Floats per row: vertex 0, the two edges, the unit front normal, the area, the radiance
  /// and whether both faces emit (1 or 0).
  // clang-format off
  enum Column : uint8_t {
    kP0x, kP0y, kP0z, kE1x, kE1y, kE1z, kE2x, kE2y, kE2z, kNx, kNy, kNz,
    kArea, kLeR, kLeG, kLeB, kDoubleSided, kColumnCount
  };
  // clang-format on

 private:
  std::vector<float> table_;   ///< kColumnCount floats per row
  std::vector<int32_t> rows_;  ///< per light index
  bool useful_ = false;
};

}  // namespace tray

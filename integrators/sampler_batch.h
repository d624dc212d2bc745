#pragma once
// A wave's next random numbers in SIMD (Highway, dynamic dispatch): the two 3D draws a path
// vertex makes (the light sample's, then the BSDF sample's), for every path of the queue at
// once, bit for bit Sampler::next3D's (docs/wavefront.md, "Random numbers in SIMD").
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/sampler.h"
#include "core/simd_lanes.h"

namespace tray {

/// The draws made ahead, one entry per path: first[k] and second[k] are what the path's
/// sampler's next two next3D() calls return.
struct SamplerDrawsAhead {
  std::vector<Vec3> first, second;
  // The kernel's inputs: key + step * dimension (Sampler::drawBase) and the reversed index.
  std::vector<uint64_t> base;
  std::vector<uint32_t> reversedIndex;
  /// Room for n entries in whole vectors (core/simd_lanes.h); never shrinks.
  void resize(size_t n);
};

/// The next two next3D() draws of many samplers of one sequence, without advancing them; a
/// path then takes them with Sampler::skip3D (PathEstimator::step's `ahead`). Needs a SIMD
/// target (hasSimdTarget, core/simd_lanes.h).
class SamplerBatch {
 public:
  /// out.first[k], out.second[k] for samplers[index[k]], k < n.
  static void drawTwo3D(Sampler::Sequence sequence, const Sampler* samplers, const uint32_t* index,
                        size_t n, SamplerDrawsAhead& out);
};

}  // namespace tray

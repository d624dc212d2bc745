#pragma once
#include <cstdint>

#include "core/math.h"

namespace tray {

/// Counter-based random numbers: each value is a hash of (pixel, sample, dimension, seed), so
/// a pixel's samples do not depend on which thread renders it or in what order.
class Sampler {
 public:
  Sampler(uint32_t pixelIndex, uint32_t sampleIndex, uint64_t seed)
      : key_(mix(mix(seed ^ 0x9e3779b97f4a7c15ull) ^ (uint64_t(pixelIndex) << 32 | sampleIndex))) {}
  /// Uniform in [0, 1).
  float next1D() { return toUnit(mix(key_ + 0xbf58476d1ce4e5b9ull * ++dimension_)); }
  Vec2 next2D() {
    float a = next1D();
    return {a, next1D()};
  }
  uint32_t dimension() const { return dimension_; }

 private:
  // SplitMix64 finaliser (Steele et al. 2014): a strong 64-bit mixing function.
  static uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  static float toUnit(uint64_t v) { return float(v >> 40) * (1.0f / 16777216.0f); }
  uint64_t key_;
  uint32_t dimension_ = 0;
};

}  // namespace tray

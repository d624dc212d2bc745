#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/options.h"
#include "core/sampler_lanes.h"
#include "core/sobol.h"

namespace tray {

/// Counter-based random numbers: each value is a function of (pixel, sample, dimension, seed),
/// so a pixel's samples do not depend on which thread renders it or in what order.
class Sampler {
 public:
  enum class Sequence : uint8_t {
    kIndependent,  ///< a hash per value: uniform, independent (Mitsuba's `independent`)
    kSobol,        ///< Owen-scrambled Sobol' in padded 1-3D groups (core/sobol.h): stratified
  };
  /// Names accepted by --sampler.
  static const std::vector<std::string>& names();
  /// --sampler: declared here, beside the sequences it names.
  static const OptionSpec& option();
  /// Resolves a name (throws tray::Error naming the choices for an unknown one).
  static Sequence parse(const std::string& name);

  Sampler(uint32_t pixelIndex, uint32_t sampleIndex, uint64_t seed,
          Sequence sequence = Sequence::kIndependent)
      : key_(samplerKeyOf<float>(seedKey(seed), pixelIndex, sampleIndex,
                                 sequence == Sequence::kSobol)),
        reversedIndex_(reverseBitsOf(sampleIndex)),
        sequence_(sequence) {}
  // The draws are core/sampler_lanes.h's, which the SIMD kernels run too.
  /// Uniform in [0, 1).
  float next1D() {
    if (sequence_ == Sequence::kIndependent)
      return independentUnitOf<float>(dimensionHashOf(key_, ++dimension_));
    return sobol1DOf<float>(dimensionHashOf(key_, ++dimension_), reversedIndex_);
  }
  /// Two dimensions; with kSobol, the pair is one 2D Sobol' point (stratified jointly).
  Vec2 next2D() {
    if (sequence_ == Sequence::kIndependent) {
      float a = next1D();
      return {a, next1D()};
    }
    return sobol2DOf<float>(dimensionHashOf(key_, dimension_ += 2), reversedIndex_);
  }
  /// Three dimensions; with kSobol one 3D Sobol' point (dimensions 0-2 at one shuffled index),
  /// its (y, z) a (0, 2)-net like next2D's pair. Independent: three next1D() values in order.
  Vec3 next3D() {
    if (sequence_ == Sequence::kIndependent) {
      const float a = next1D(), b = next1D();
      return {a, b, next1D()};
    }
    return sobol3DOf<float>(dimensionHashOf(key_, dimension_ += 3), reversedIndex_);
  }
  uint32_t dimension() const { return dimension_; }
  /// A value's hash input is key + kDimensionStep * its dimension (mod 2^64).
  static constexpr uint64_t kDimensionStep = kSamplerDimensionStep;
  Sequence sequence() const { return sequence_; }
  uint32_t reversedIndex() const { return reversedIndex_; }
  /// key + step * dimension (mod 2^64): the next draws' hashes are of drawBase() + step * j,
  /// j = 1, 2, ... (integrators/sampler_batch.h makes them ahead in SIMD).
  uint64_t drawBase() const { return key_ + kDimensionStep * dimension_; }
  /// Advances past a next3D() whose value was drawn ahead (integrators/sampler_batch.h): both
  /// sequences take three dimensions per 3D draw.
  void skip3D() { dimension_ += 3; }
  /// The seed's own hash, the first step of every sample's key (the constructor's, and the
  /// batch kernel's in integrators/camera_batch.cpp, which computes it once per render).
  static uint64_t seedKey(uint64_t seed) { return mixOf(seed ^ 0x9e3779b97f4a7c15ull); }
  /// The sampler whose state a batch kernel computed (integrators/camera_batch.cpp runs the
  /// constructor's and next2D's core/sampler_lanes.h over many samples at once).
  static Sampler fromState(uint64_t key, uint32_t reversedIndex, uint32_t dimension,
                           Sequence sequence) {
    return Sampler(StateTag{}, key, reversedIndex, dimension, sequence);
  }
  /// The same state: every number drawn from here on is the same.
  bool operator==(const Sampler&) const = default;
  /// Dimensions set apart for one use each, far beyond any path's count: drawing them with
  /// reserved1D leaves every other number of the sample as it was.
  static constexpr uint32_t kShutterDimension = 0x40000000u;  ///< the camera ray's time
  /// The wavelength of a path through dispersive glass (KHR_materials_dispersion).
  static constexpr uint32_t kWavelengthDimension = 0x40000001u;
  /// Uniform in [0, 1) at a fixed `dimension`, without advancing the counter: a feature that
  /// is off draws nothing, and on it changes no other number (so images without it keep every
  /// bit). With kSobol the values over a pixel's samples are one stratified 1D sequence.
  float reserved1D(uint32_t dimension) const {
    const uint64_t h = dimensionHashOf(key_, dimension);
    if (sequence_ == Sequence::kIndependent) return independentUnitOf<float>(h);
    return sobol1DOf<float>(h, reversedIndex_);
  }

 private:
  struct StateTag {};  // apart from the public constructor's overloads
  Sampler(StateTag, uint64_t key, uint32_t reversedIndex, uint32_t dimension, Sequence sequence)
      : key_(key), reversedIndex_(reversedIndex), dimension_(dimension), sequence_(sequence) {}
  uint64_t key_;
  uint32_t reversedIndex_;  ///< the sample index, bit-reversed for the Sobol' shuffle
  uint32_t dimension_ = 0;
  Sequence sequence_;
};

}  // namespace tray

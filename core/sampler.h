#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/options.h"
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
      // Independent: one key per sample. Sobol': one per pixel, the same for all its samples
      // (they form one scrambled sequence), with the sample index kept apart.
      : key_(mix(seedKey(seed) ^ (sequence == Sequence::kIndependent
                                      ? uint64_t(pixelIndex) << 32 | sampleIndex
                                      : uint64_t(pixelIndex) << 32 ^ 0x5851f42d4c957f2dull))),
        reversedIndex_(sobol::reverseBits(sampleIndex)),
        sequence_(sequence) {}
  /// Uniform in [0, 1).
  float next1D() {
    if (sequence_ == Sequence::kIndependent)
      return toUnit(mix(key_ + kDimensionStep * ++dimension_));
    const uint64_t h = dimensionHash(++dimension_);
    const uint32_t index = sobol::shuffleReversed(reversedIndex_, uint32_t(h));
    return sobol::toUnit(sobol::scrambledDimension0(index, uint32_t(h >> 32)));
  }
  /// Two dimensions; with kSobol, the pair is one 2D Sobol' point (stratified jointly).
  Vec2 next2D() {
    if (sequence_ == Sequence::kIndependent) {
      float a = next1D();
      return {a, next1D()};
    }
    const uint64_t h = dimensionHash(dimension_ += 2);
    const uint32_t index = sobol::shuffleReversed(reversedIndex_, uint32_t(h));
    // Three 32-bit seeds from one 64-bit hash and a cheap odd-multiply remix of it.
    const uint32_t seedX = uint32_t(h >> 32), seedY = uint32_t((h * 0x9e3779b97f4a7c15ull) >> 32);
    return {sobol::toUnit(sobol::scrambledDimension0(index, seedX)),
            sobol::toUnit(sobol::scrambledDimension1(index, seedY))};
  }
  /// Three dimensions; with kSobol one 3D Sobol' point (dimensions 0-2 at one shuffled index),
  /// its (y, z) a (0, 2)-net like next2D's pair. Independent: three next1D() values in order.
  Vec3 next3D() {
    if (sequence_ == Sequence::kIndependent) {
      const float a = next1D(), b = next1D();
      return {a, b, next1D()};
    }
    const uint64_t h = dimensionHash(dimension_ += 3);
    const uint32_t index = sobol::shuffleReversed(reversedIndex_, uint32_t(h));
    // The shuffle and three scrambles need four 32-bit seeds: two 64-bit hashes.
    const uint64_t h2 = mix(h ^ 0x94d049bb133111ebull);
    const uint32_t seedX = uint32_t(h2 >> 32), seedY = uint32_t(h >> 32), seedZ = uint32_t(h2);
    return {sobol::toUnit(sobol::scrambledDimension2(index, seedX)),
            sobol::toUnit(sobol::scrambledDimension0(index, seedY)),
            sobol::toUnit(sobol::scrambledDimension1(index, seedZ))};
  }
  uint32_t dimension() const { return dimension_; }
  /// A value's hash input is key + kDimensionStep * its dimension (mod 2^64); the SIMD kernels
  /// (integrators/sampler_simd-inl.h) repeat it.
  static constexpr uint64_t kDimensionStep = 0xbf58476d1ce4e5b9ull;
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
  static uint64_t seedKey(uint64_t seed) { return mix(seed ^ 0x9e3779b97f4a7c15ull); }
  /// The sampler whose state a batch kernel computed (integrators/camera_batch.cpp repeats the
  /// constructor's and next2D's hashes over many samples at once).
  static Sampler fromState(uint64_t key, uint32_t reversedIndex, uint32_t dimension,
                           Sequence sequence) {
    return Sampler(StateTag{}, key, reversedIndex, dimension, sequence);
  }
  /// The same state: every number drawn from here on is the same.
  bool operator==(const Sampler&) const = default;
  /// Dimensions set apart for one use each, far beyond any path's count: drawing them with
  /// reserved1D leaves every other number of the sample as it was.
  static constexpr uint32_t kShutterDimension = 0x40000000u;  ///< the camera ray's time
  /// Uniform in [0, 1) at a fixed `dimension`, without advancing the counter: a feature that
  /// is off draws nothing, and on it changes no other number (so images without it keep every
  /// bit). With kSobol the values over a pixel's samples are one stratified 1D sequence.
  float reserved1D(uint32_t dimension) const {
    if (sequence_ == Sequence::kIndependent) return toUnit(mix(key_ + kDimensionStep * dimension));
    const uint64_t h = dimensionHash(dimension);
    const uint32_t index = sobol::shuffleReversed(reversedIndex_, uint32_t(h));
    return sobol::toUnit(sobol::scrambledDimension0(index, uint32_t(h >> 32)));
  }

 private:
  struct StateTag {};  // apart from the public constructor's overloads
  Sampler(StateTag, uint64_t key, uint32_t reversedIndex, uint32_t dimension, Sequence sequence)
      : key_(key), reversedIndex_(reversedIndex), dimension_(dimension), sequence_(sequence) {}
  // SplitMix64 finaliser (Steele et al. 2014): a strong 64-bit mixing function.
  static uint64_t mix(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  static float toUnit(uint64_t v) { return float(v >> 40) * (1.0f / 16777216.0f); }
  /// Sobol': per pixel and dimension, the seed of its shuffle and scrambles.
  uint64_t dimensionHash(uint32_t dimension) const {
    return mix(key_ + kDimensionStep * dimension);
  }
  uint64_t key_;
  uint32_t reversedIndex_;  ///< the sample index, bit-reversed for the Sobol' shuffle
  uint32_t dimension_ = 0;
  Sequence sequence_;
};

}  // namespace tray

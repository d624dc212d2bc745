#pragma once
// Owen-scrambled Sobol' points in padded 2D pairs: the low-discrepancy sequence behind
// `--sampler sobol`. Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)), with the
// faster hash of pbrt-v4's FastOwenScrambler (Vegdahl); the layout is pbrt-v4's
// PaddedSobolSampler: each pair of dimensions takes the first two Sobol' dimensions at its own
// shuffle of the sample index, so pairs do not correlate with one another. The formulas are
// written once, over the lane type, in core/sampler_lanes.h (the SIMD kernels run the same
// text); these are their scalar names.
#include <cstdint>

#include "core/sampler_lanes.h"
#include "core/sobol_tables.h"

namespace tray::sobol {

inline uint32_t reverseBits(uint32_t v) {
  return reverseBitsOf(v);
}

/// The hash behind Owen scrambling, on bit-reversed digits (core/sampler_lanes.h).
inline uint32_t carryHash(uint32_t v, uint32_t seed) {
  return carryHashOf(v, seed);
}

/// Nested uniform (Owen) scrambling of the binary digits of v (most significant digit first):
/// each digit is flipped by a hash of the digits above it.
inline uint32_t owenScramble(uint32_t v, uint32_t seed) {
  return reverseBits(carryHash(reverseBits(v), seed));
}

/// Sobol' dimension 0 (van der Corput in base 2) as 32 fixed-point bits.
inline uint32_t dimension0(uint32_t index) {
  return reverseBits(index);
}

/// reverseBits(dimension1(index)), reverseBits(dimension2(index)).
inline uint32_t reversedDimension1(uint32_t index) {
  return sobolReversedDimension1Of(index);
}
inline uint32_t reversedDimension2(uint32_t index) {
  return sobolReversedDimension2Of(index);
}
inline uint32_t dimension1(uint32_t index) {
  return reverseBits(reversedDimension1(index));
}
inline uint32_t dimension2(uint32_t index) {
  return reverseBits(reversedDimension2(index));
}

/// A permutation of sample indices under which every aligned block of 2^k indices maps to an
/// aligned block of 2^k (Burley 2020 section 4: the index scrambled as if it were a value), so
/// the first 2^k samples of a pixel stay a (0, k, 2)-net in each pair of dimensions.
inline uint32_t shuffle(uint32_t index, uint32_t seed) {
  return owenScramble(index, seed);
}
/// The same from reverseBits(index), which a sampler computes once for all its dimensions.
inline uint32_t shuffleReversed(uint32_t reversedIndex, uint32_t seed) {
  return sobolShuffleReversedOf(reversedIndex, seed);
}

/// Owen-scrambled dimensions 0, 1 and 2 at a (shuffled) index: owenScramble(dimensionN(index))
/// with the bit reversals that cancel left out.
inline uint32_t scrambledDimension0(uint32_t index, uint32_t seed) {
  return sobolScrambled0Of(index, seed);
}
inline uint32_t scrambledDimension1(uint32_t index, uint32_t seed) {
  return sobolScrambled1Of(index, seed);
}
inline uint32_t scrambledDimension2(uint32_t index, uint32_t seed) {
  return sobolScrambled2Of(index, seed);
}

/// Fixed-point bits to [0, 1): the top 24 bits, so 1 is never reached.
inline float toUnit(uint32_t bits) {
  return sobolUnitOf<float>(bits);
}

}  // namespace tray::sobol

#pragma once
// Owen-scrambled Sobol' points in padded 2D pairs: the low-discrepancy sequence behind
// `--sampler sobol`. Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)), with the
// faster hash of pbrt-v4's FastOwenScrambler (Vegdahl); the layout is pbrt-v4's
// PaddedSobolSampler: each pair of dimensions takes the first two Sobol' dimensions at its own
// shuffle of the sample index, so pairs do not correlate with one another.
#include <cstdint>

namespace tray::sobol {

inline uint32_t reverseBits(uint32_t v) {
  v = __builtin_bswap32(v);  // bytes, then the bits within each byte
  v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
  v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
  return ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
}

/// The hash behind Owen scrambling, on bit-reversed digits: a multiply carries only from lower
/// to higher bits, so output bit k depends on input bits 0..k alone.
inline uint32_t carryHash(uint32_t v, uint32_t seed) {
  v ^= v * 0x3d20adeau;
  v += seed;
  v *= (seed >> 16) | 1u;
  v ^= v * 0x05526c56u;
  v ^= v * 0x53a22864u;
  return v;
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

/// Sobol' dimension 1 (primitive polynomial x + 1: direction numbers v_{k+1} = v_k ^ v_k >> 1),
/// by the definition: the XOR of the direction numbers the index bits select.
constexpr uint32_t dimension1Reference(uint32_t index) {
  uint32_t result = 0;
  for (uint32_t v = 1u << 31; index; index >>= 1, v ^= v >> 1)
    if (index & 1u) result ^= v;
  return result;
}

namespace detail {
constexpr uint32_t reverseBitsSlow(uint32_t v) {
  uint32_t r = 0;
  for (int i = 0; i < 32; ++i, v >>= 1) r = (r << 1) | (v & 1u);
  return r;
}
/// dimension1 of each byte of the index in each of its four positions, bit-reversed (what
/// Owen scrambling takes): the matrix-vector product over GF(2) as four lookups (4 KB),
/// instead of a data-dependent loop over 32 bits.
struct Dimension1Tables {
  uint32_t byte[4][256];
  constexpr Dimension1Tables() : byte{} {
    for (int b = 0; b < 4; ++b)
      for (uint32_t i = 0; i < 256; ++i)
        byte[b][i] = reverseBitsSlow(dimension1Reference(i << (8 * b)));
  }
};
inline constexpr Dimension1Tables kDimension1;
}  // namespace detail

/// reverseBits(dimension1(index)).
inline uint32_t reversedDimension1(uint32_t index) {
  const auto& t = detail::kDimension1.byte;
  return t[0][index & 255u] ^ t[1][(index >> 8) & 255u] ^ t[2][(index >> 16) & 255u] ^
         t[3][index >> 24];
}

inline uint32_t dimension1(uint32_t index) {
  return reverseBits(reversedDimension1(index));
}

/// A permutation of sample indices under which every aligned block of 2^k indices maps to an
/// aligned block of 2^k (Burley 2020 section 4: the index scrambled as if it were a value), so
/// the first 2^k samples of a pixel stay a (0, k, 2)-net in each pair of dimensions.
inline uint32_t shuffle(uint32_t index, uint32_t seed) {
  return owenScramble(index, seed);
}

/// Owen-scrambled dimensions 0 and 1 at a (shuffled) index: owenScramble(dimensionN(index))
/// with the bit reversals that cancel left out.
inline uint32_t scrambledDimension0(uint32_t index, uint32_t seed) {
  return reverseBits(carryHash(index, seed));
}
inline uint32_t scrambledDimension1(uint32_t index, uint32_t seed) {
  return reverseBits(carryHash(reversedDimension1(index), seed));
}

/// Fixed-point bits to [0, 1): the top 24 bits, so 1 is never reached.
inline float toUnit(uint32_t bits) {
  return float(bits >> 8) * (1.0f / 16777216.0f);
}

}  // namespace tray::sobol

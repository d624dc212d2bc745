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

/// Direction numbers v_1..v_32 (as 32-bit fixed point) of the Sobol' dimension with primitive
/// polynomial of degree s and inner coefficients a (Bratley & Fox 1988, recurrence
/// v_k = a_1 v_(k-1) ^ ... ^ a_(s-1) v_(k-s+1) ^ v_(k-s) ^ v_(k-s) >> s), from initial m_1..m_s
/// (Joe & Kuo 2008, new-joe-kuo-6.21201: dimension 2 has s = 1, m = 1; dimension 3 s = 2, a = 1,
/// m = 1, 3).
struct DirectionNumbers {
  uint32_t v[32];
  constexpr DirectionNumbers(int s, uint32_t a, const uint32_t* m) : v{} {
    for (int k = 0; k < s; ++k) v[k] = m[k] << (31 - k);
    for (int k = s; k < 32; ++k) {
      uint32_t x = v[k - s] ^ (v[k - s] >> s);
      for (int j = 1; j < s; ++j)
        if ((a >> (s - 1 - j)) & 1u) x ^= v[k - j];
      v[k] = x;
    }
  }
  /// The sample at `index`: the XOR of the direction numbers its bits select.
  constexpr uint32_t sample(uint32_t index) const {
    uint32_t result = 0;
    for (int k = 0; index; index >>= 1, ++k)
      if (index & 1u) result ^= v[k];
    return result;
  }
};
inline constexpr uint32_t kM1[1] = {1}, kM2[2] = {1, 3};
inline constexpr DirectionNumbers kDimension1Numbers(1, 0, kM1), kDimension2Numbers(2, 1, kM2);

/// Sobol' dimensions 1 and 2 by the definition (tests compare the tables against these).
constexpr uint32_t dimension1Reference(uint32_t index) {
  return kDimension1Numbers.sample(index);
}
constexpr uint32_t dimension2Reference(uint32_t index) {
  return kDimension2Numbers.sample(index);
}

namespace detail {
constexpr uint32_t reverseBitsSlow(uint32_t v) {
  uint32_t r = 0;
  for (int i = 0; i < 32; ++i, v >>= 1) r = (r << 1) | (v & 1u);
  return r;
}
/// A dimension's value for each byte of the index in each of its four positions, bit-reversed
/// (what Owen scrambling takes): the matrix-vector product over GF(2) as four lookups (4 KB
/// per dimension), instead of a data-dependent loop over 32 bits.
struct ReversedTables {
  uint32_t byte[4][256];
  constexpr explicit ReversedTables(const DirectionNumbers& d) : byte{} {
    for (int b = 0; b < 4; ++b)
      for (uint32_t i = 0; i < 256; ++i) byte[b][i] = reverseBitsSlow(d.sample(i << (8 * b)));
  }
  uint32_t operator()(uint32_t index) const {
    return byte[0][index & 255u] ^ byte[1][(index >> 8) & 255u] ^ byte[2][(index >> 16) & 255u] ^
           byte[3][index >> 24];
  }
};
inline constexpr ReversedTables kDimension1(kDimension1Numbers), kDimension2(kDimension2Numbers);
}  // namespace detail

/// reverseBits(dimension1(index)), reverseBits(dimension2(index)).
inline uint32_t reversedDimension1(uint32_t index) {
  return detail::kDimension1(index);
}
inline uint32_t reversedDimension2(uint32_t index) {
  return detail::kDimension2(index);
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
  return reverseBits(carryHash(reversedIndex, seed));
}

/// Owen-scrambled dimensions 0 and 1 at a (shuffled) index: owenScramble(dimensionN(index))
/// with the bit reversals that cancel left out.
inline uint32_t scrambledDimension0(uint32_t index, uint32_t seed) {
  return reverseBits(carryHash(index, seed));
}
inline uint32_t scrambledDimension1(uint32_t index, uint32_t seed) {
  return reverseBits(carryHash(reversedDimension1(index), seed));
}
inline uint32_t scrambledDimension2(uint32_t index, uint32_t seed) {
  return reverseBits(carryHash(reversedDimension2(index), seed));
}

/// Fixed-point bits to [0, 1): the top 24 bits, so 1 is never reached.
inline float toUnit(uint32_t bits) {
  return float(bits >> 8) * (1.0f / 16777216.0f);
}

}  // namespace tray::sobol

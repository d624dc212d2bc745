#pragma once
// Sobol' dimensions 1 and 2 by their definition (direction numbers), and their byte tables: the
// constant data behind core/sobol.h and core/sampler_lanes.h.
#include <cstdint>

namespace tray::sobol {

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

/// Sobol' dimensions 1 and 2 by the definition (tests compare the fast forms against these).
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
/// per dimension), instead of a data-dependent loop over 32 bits (core/sampler_lanes.h).
struct ReversedTables {
  uint32_t byte[4][256];
  constexpr explicit ReversedTables(const DirectionNumbers& d) : byte{} {
    for (int b = 0; b < 4; ++b)
      for (uint32_t i = 0; i < 256; ++i) byte[b][i] = reverseBitsSlow(d.sample(i << (8 * b)));
  }
};
inline constexpr ReversedTables kDimension1(kDimension1Numbers), kDimension2(kDimension2Numbers);
}  // namespace detail

}  // namespace tray::sobol

// The counter-based Sampler's numbers (core/sampler.h, core/sobol.h), written once over the lane
// type (core/lane_ops.h, docs/lanes.md): SplitMix64's hash of a key and a dimension, the
// independent sequence's 24-bit uniforms, and Owen-scrambled Sobol' (Burley 2020 with pbrt-v4's
// FastOwenScrambler hash, pbrt-v4's padded layout). Sampler and core/sobol.h call these with
// scalar integers; the SIMD kernels integrators/sampler_batch.cpp and camera_batch.cpp include
// this file again in each target's pass with TRAY_LANES_SIMD defined, where a 32-bit lane is a
// UintVec and a 64-bit one a U64Vec (two Highway vectors per FloatVec).
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_SAMPLER_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_SAMPLER_LANES_SIMD_
#undef TRAY_CORE_SAMPLER_LANES_SIMD_
#else
#define TRAY_CORE_SAMPLER_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_SAMPLER_LANES_SCALAR_)
#define TRAY_CORE_SAMPLER_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include <cstdint>

#include "core/lane_ops.h"
#include "core/sobol_tables.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

// The small steps below are inlined whatever the context, also with scalars (HWY_INLINE does so
// for vectors); the draws that compose them (samplerKeyOf, sobol1DOf, 2DOf, 3DOf) are left to
// GCC's heuristics, like the scalar code before them. Left to GCC, the steps moved its inlining
// of the path estimator around and cost path-scalar 3-4% (path_bench, Cornell box); so, the
// same speed.
#ifdef TRAY_LANES_SIMD
#define TRAY_SAMPLER_LANE TRAY_LANE
#else
#define TRAY_SAMPLER_LANE [[gnu::always_inline]] inline
#endif

/// A value's hash input is key + kSamplerDimensionStep * its dimension (mod 2^64).
inline constexpr uint64_t kSamplerDimensionStep = 0xbf58476d1ce4e5b9ull;

/// SplitMix64's finaliser (Steele et al. 2014): a strong 64-bit mixing function. U64: U64Of<F>.
template <class U64>
TRAY_SAMPLER_LANE U64 mixOf(U64 z) {
  z = (z ^ (z >> 30)) * U64(0xbf58476d1ce4e5b9ull);
  z = (z ^ (z >> 27)) * U64(0x94d049bb133111ebull);
  return z ^ (z >> 31);
}

/// The sampler's key: its seed's hash (Sampler::seedKey) mixed with the pixel and, for
/// independent numbers, the sample (one key per sample); Sobol' has one key per pixel, the same
/// for all its samples (they form one scrambled sequence), with the sample index kept apart.
template <class F>
TRAY_LANE U64Of<F> samplerKeyOf(uint64_t seedKey, UintOf<F> pixel, UintOf<F> sample, bool sobol) {
  using U64 = U64Of<F>;
  const U64 high = widenOf(pixel) << 32;
  return mixOf(U64(seedKey) ^ (sobol ? high ^ U64(0x5851f42d4c957f2dull) : high | widenOf(sample)));
}

/// The hash of the dimension `dimensions` on from base (a key, or Sampler::drawBase).
template <class U64>
TRAY_SAMPLER_LANE U64 dimensionHashOf(U64 base, uint64_t dimensions) {
  return mixOf(base + U64(kSamplerDimensionStep * dimensions));
}

/// float(bits) / 2^24 for bits < 2^24: exact.
template <class F>
TRAY_SAMPLER_LANE F unitOf24Bits(UintOf<F> bits) {
  return toFloatOf(intFromBits(bits)) * F(1.0f / 16777216.0f);
}

/// An independent uniform in [0, 1) from its 64-bit hash: the top 24 bits.
template <class F>
TRAY_SAMPLER_LANE F independentUnitOf(U64Of<F> hash) {
  return unitOf24Bits<F>(low32Of(hash >> 40));
}

/// Sobol' fixed-point bits to [0, 1): the top 24 bits, so 1 is never reached.
template <class F>
TRAY_SAMPLER_LANE F sobolUnitOf(UintOf<F> bits) {
  return unitOf24Bits<F>(bits >> 8);
}

/// The hash behind Owen scrambling, on bit-reversed digits: a multiply carries only from lower
/// to higher bits, so output bit k depends on input bits 0..k alone. U: UintOf<F>.
template <class U>
TRAY_SAMPLER_LANE U carryHashOf(U v, U seed) {
  v = v ^ v * U(0x3d20adeau);
  v = v + seed;
  v = v * ((seed >> 16) | U(1u));
  v = v ^ v * U(0x05526c56u);
  return v ^ v * U(0x53a22864u);
}

/// reverseBits(a Sobol' dimension at index) from its byte tables (core/sobol_tables.h, raw): the
/// XOR of the entries of the index's four bytes, the matrix-vector product over GF(2). For
/// dimension 1 this is faster for one sampler than computing it (dimension 1's generator,
/// Pascal's matrix mod 2, also has a butterfly form: measured, the 3D draw takes 7% longer with
/// it), so both dimensions and both lane types look up the tables (a vector: gathers).
template <class U>
TRAY_SAMPLER_LANE U sobolReversedOf(const uint32_t (&t)[4][256], U v) {
  return gatherOf(t[0], v & U(255u)) ^ gatherOf(t[1], (v >> 8) & U(255u)) ^
         gatherOf(t[2], (v >> 16) & U(255u)) ^ gatherOf(t[3], v >> 24);
}
template <class U>
TRAY_SAMPLER_LANE U sobolReversedDimension1Of(U index) {
  return sobolReversedOf(sobol::detail::kDimension1.byte, index);
}
template <class U>
TRAY_SAMPLER_LANE U sobolReversedDimension2Of(U index) {
  return sobolReversedOf(sobol::detail::kDimension2.byte, index);
}

/// The shuffled sample index from reverseBits(index), which a sampler computes once for all its
/// dimensions: Owen-scrambled as if it were a value (Burley 2020 section 4), so every aligned
/// block of 2^k indices maps to an aligned block of 2^k.
template <class U>
TRAY_SAMPLER_LANE U sobolShuffleReversedOf(U reversedIndex, U seed) {
  return reverseBitsOf(carryHashOf(reversedIndex, seed));
}

/// Owen-scrambled Sobol' dimensions 0, 1 and 2 at a (shuffled) index, as 32 fixed-point bits:
/// owenScramble(dimensionN(index)) with the bit reversals that cancel left out.
template <class U>
TRAY_SAMPLER_LANE U sobolScrambled0Of(U index, U seed) {
  return reverseBitsOf(carryHashOf(index, seed));
}
template <class U>
TRAY_SAMPLER_LANE U sobolScrambled1Of(U index, U seed) {
  return reverseBitsOf(carryHashOf(sobolReversedDimension1Of(index), seed));
}
template <class U>
TRAY_SAMPLER_LANE U sobolScrambled2Of(U index, U seed) {
  return reverseBitsOf(carryHashOf(sobolReversedDimension2Of(index), seed));
}

/// Sampler::next1D with Sobol', from the dimension's hash: dimension 0 at the shuffled index.
template <class F>
TRAY_LANE F sobol1DOf(U64Of<F> hash, UintOf<F> reversedIndex) {
  const UintOf<F> index = sobolShuffleReversedOf(reversedIndex, low32Of(hash));
  return sobolUnitOf<F>(sobolScrambled0Of(index, high32Of(hash)));
}

/// Sampler::next2D with Sobol': one 2D Sobol' point (dimensions 0 and 1, stratified jointly);
/// three 32-bit seeds from one 64-bit hash and a cheap odd-multiply remix of it.
template <class F>
TRAY_LANE Vec2Of<F> sobol2DOf(U64Of<F> hash, UintOf<F> reversedIndex) {
  using U = UintOf<F>;
  const U index = sobolShuffleReversedOf(reversedIndex, low32Of(hash));
  const U seedX = high32Of(hash), seedY = high32Of(hash * U64Of<F>(0x9e3779b97f4a7c15ull));
  return {sobolUnitOf<F>(sobolScrambled0Of(index, seedX)),
          sobolUnitOf<F>(sobolScrambled1Of(index, seedY))};
}

/// Sampler::next3D with Sobol': one 3D Sobol' point (dimensions 2, 0, 1 at one shuffled index),
/// its (y, z) a (0, 2)-net like sobol2DOf's pair. The shuffle and three scrambles need four
/// 32-bit seeds: two 64-bit hashes.
template <class F>
TRAY_LANE Vec3Of<F> sobol3DOf(U64Of<F> hash, UintOf<F> reversedIndex) {
  using U = UintOf<F>;
  const U index = sobolShuffleReversedOf(reversedIndex, low32Of(hash));
  const U64Of<F> hash2 = mixOf(hash ^ U64Of<F>(0x94d049bb133111ebull));
  const U seedX = high32Of(hash2), seedY = high32Of(hash), seedZ = low32Of(hash2);
  return {sobolUnitOf<F>(sobolScrambled2Of(index, seedX)),
          sobolUnitOf<F>(sobolScrambled0Of(index, seedY)),
          sobolUnitOf<F>(sobolScrambled1Of(index, seedZ))};
}

#undef TRAY_SAMPLER_LANE
#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

// The counter-based Sampler's hashes and Sobol' scrambles (core/sampler.h, core/sobol.h) as
// Highway vector functions, shared by the SIMD kernels that repeat them bit for bit
// (integrators/camera_batch.cpp, integrators/sampler_batch.cpp). Highway's -inl.h convention: included once
// per target after hwy/highway.h, guarded per target by HWY_TARGET_TOGGLE.
#if defined(TRAY_CORE_SAMPLER_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_SAMPLER_SIMD_INL_H_
#undef TRAY_CORE_SAMPLER_SIMD_INL_H_
#else
#define TRAY_CORE_SAMPLER_SIMD_INL_H_
#endif

#include <cstdint>

#include "core/sampler.h"
#include "core/sobol.h"
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET != HWY_SCALAR  // the kernels pair 64-bit halves: no single-lane version
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using DU = hn::RebindToUnsigned<DF>;
using D64 = hn::Repartition<uint64_t, DU>;  // half as many lanes as DU
using DU8 = hn::Repartition<uint8_t, DU>;
using DHalf = hn::Rebind<uint32_t, D64>;  // DU's lower or upper half
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using VU = hn::Vec<DU>;
using V64 = hn::Vec<D64>;

// Sampler's constants (core/sampler.h).
constexpr uint64_t kDimensionStep = Sampler::kDimensionStep, kGolden = 0x9e3779b97f4a7c15ull;

/// Sampler::mix, SplitMix64's finaliser.
HWY_INLINE V64 Mix(V64 z) {
  const D64 d;
  z = hn::Xor(z, hn::ShiftRight<30>(z)) * hn::Set(d, 0xbf58476d1ce4e5b9ull);
  z = hn::Xor(z, hn::ShiftRight<27>(z)) * hn::Set(d, 0x94d049bb133111ebull);
  return hn::Xor(z, hn::ShiftRight<31>(z));
}

/// The low (even) and high (odd) 32-bit halves of two u64 vectors' lanes, in lane order.
HWY_INLINE VU Low32(V64 lower, V64 upper) {
  const DU du;
  return hn::ConcatEven(du, hn::BitCast(du, upper), hn::BitCast(du, lower));
}
HWY_INLINE VU High32(V64 lower, V64 upper) {
  const DU du;
  return hn::ConcatOdd(du, hn::BitCast(du, upper), hn::BitCast(du, lower));
}

/// float(bits) * 2^-24 for bits < 2^24 (exact either way): Sampler's and sobol's toUnit.
HWY_INLINE VF UnitOf24Bits(VU bits) {
  const DF df;
  return hn::ConvertTo(df, hn::BitCast(DI(), bits)) * hn::Set(df, 1.0f / 16777216.0f);
}

/// sobol::reverseBits: the bytes of each lane reversed, then the bits of each byte by a table of
/// reversed nibbles.
HWY_INLINE VU ReverseBits(VU v) {
  const DU du;
  const DU8 d8;
  alignas(16) static constexpr uint8_t kByteSwap[16] = {3,  2,  1, 0, 7,  6,  5,  4,
                                                        11, 10, 9, 8, 15, 14, 13, 12};
  alignas(16) static constexpr uint8_t kNibble[16] = {0x0, 0x8, 0x4, 0xc, 0x2, 0xa, 0x6, 0xe,
                                                      0x1, 0x9, 0x5, 0xd, 0x3, 0xb, 0x7, 0xf};
  const auto swapped = hn::TableLookupBytes(hn::BitCast(d8, v), hn::LoadDup128(d8, kByteSwap));
  const auto lowNibbles = hn::And(swapped, hn::Set(d8, 0x0f));
  const auto highNibbles = hn::BitCast(
      d8, hn::And(hn::ShiftRight<4>(hn::BitCast(du, swapped)), hn::Set(du, 0x0f0f0f0fu)));
  const auto table = hn::LoadDup128(d8, kNibble);
  const VU low = hn::BitCast(du, hn::TableLookupBytes(table, lowNibbles));
  return hn::Or(hn::ShiftLeft<4>(low), hn::BitCast(du, hn::TableLookupBytes(table, highNibbles)));
}

/// sobol::carryHash.
HWY_INLINE VU CarryHash(VU v, VU seed) {
  const DU du;
  v = hn::Xor(v, v * hn::Set(du, 0x3d20adeau));
  v = v + seed;
  v = v * hn::Or(hn::ShiftRight<16>(seed), hn::Set(du, 1u));
  v = hn::Xor(v, v * hn::Set(du, 0x05526c56u));
  return hn::Xor(v, v * hn::Set(du, 0x53a22864u));
}

/// sobol::reversedDimension1 without its tables: Sobol' dimension 1's generator is Pascal's
/// matrix mod 2, whose reversed column k has bit j set iff j's bits are a subset of k's (Lucas's
/// theorem), so output bit j is the XOR of the index bits k that contain j: a superset-sum
/// (zeta) transform over the 5-bit positions, one butterfly per position bit.
HWY_INLINE VU ReversedDimension1(VU v) {
  const DU du;
  v = hn::Xor(v, hn::And(hn::ShiftRight<1>(v), hn::Set(du, 0x55555555u)));
  v = hn::Xor(v, hn::And(hn::ShiftRight<2>(v), hn::Set(du, 0x33333333u)));
  v = hn::Xor(v, hn::And(hn::ShiftRight<4>(v), hn::Set(du, 0x0f0f0f0fu)));
  v = hn::Xor(v, hn::And(hn::ShiftRight<8>(v), hn::Set(du, 0x00ff00ffu)));
  return hn::Xor(v, hn::ShiftRight<16>(v));
}

/// sobol::reversedDimension2: its four byte tables, gathered (dimension 2's generator has no
/// butterfly form like dimension 1's).
HWY_INLINE VU ReversedDimension2(VU v) {
  const DU du;
  const DI di;
  const auto& t = sobol::detail::kDimension2.byte;
  const VU byte = hn::Set(du, 255u);
  const VU b0 = hn::GatherIndex(du, t[0], hn::BitCast(di, hn::And(v, byte)));
  const VU b1 = hn::GatherIndex(du, t[1], hn::BitCast(di, hn::And(hn::ShiftRight<8>(v), byte)));
  const VU b2 = hn::GatherIndex(du, t[2], hn::BitCast(di, hn::And(hn::ShiftRight<16>(v), byte)));
  const VU b3 = hn::GatherIndex(du, t[3], hn::BitCast(di, hn::ShiftRight<24>(v)));
  return hn::Xor(hn::Xor(hn::Xor(b0, b1), b2), b3);
}

#endif  // HWY_TARGET != HWY_SCALAR
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#endif  // TRAY_CORE_SAMPLER_SIMD_INL_H_

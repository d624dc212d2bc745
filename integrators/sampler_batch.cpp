// Highway's dynamic dispatch, as integrators/camera_batch.cpp: compiled once per x86 target. Integer
// hashes and one exact int-to-float conversion per value: the same bits on every target.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/sampler_batch.cpp"
#include "integrators/sampler_batch.h"

#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: the sampler's hashes and Sobol' scrambles in SIMD.
#include "integrators/sampler_simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// Without a SIMD target (hasSimdTarget) the wavefront draws as it goes: never called.
void DrawTwo3D(int32_t, size_t, const uint64_t*, const uint32_t*, Vec3*, Vec3*) {}
#else
static_assert(HWY_MAX_BYTES / sizeof(float) <= kMaxSimdLanes);

/// Sampler::next1D with independent numbers, j dimensions on: toUnit(mix(base + step j)).
HWY_INLINE VF Independent(const V64 base[2], uint64_t j) {
  const D64 d64;
  V64 top[2];
  for (int h = 0; h < 2; ++h)
    top[h] = hn::ShiftRight<40>(Mix(base[h] + hn::Set(d64, kDimensionStep * j)));
  return UnitOf24Bits(Low32(top[0], top[1]));
}

/// Sampler::next3D with Sobol', the hash of dimension `j` on (j = 3: the next draw): the
/// shuffled index, then dimensions 2, 0 and 1 scrambled with seeds from two 64-bit hashes.
HWY_INLINE void Sobol3D(const V64 base[2], VU reversed, uint64_t j, VF& x, VF& y, VF& z) {
  const D64 d64;
  V64 hash[2], remix[2];
  for (int h = 0; h < 2; ++h) {
    hash[h] = Mix(base[h] + hn::Set(d64, kDimensionStep * j));
    remix[h] = Mix(hn::Xor(hash[h], hn::Set(d64, 0x94d049bb133111ebull)));
  }
  const VU index = ReverseBits(CarryHash(reversed, Low32(hash[0], hash[1])));
  const VU seedX = High32(remix[0], remix[1]), seedY = High32(hash[0], hash[1]),
           seedZ = Low32(remix[0], remix[1]);
  x = UnitOf24Bits(hn::ShiftRight<8>(ReverseBits(CarryHash(ReversedDimension2(index), seedX))));
  y = UnitOf24Bits(hn::ShiftRight<8>(ReverseBits(CarryHash(index, seedY))));
  z = UnitOf24Bits(hn::ShiftRight<8>(ReverseBits(CarryHash(ReversedDimension1(index), seedZ))));
}

/// One vector of samplers from entry k: their next two 3D draws, as Vec3s (x, y, z
/// interleaved) at first + k and second + k.
HWY_INLINE void Block(int32_t sobol, const uint64_t* base, const uint32_t* reversedIndex,
                      Vec3* first, Vec3* second) {
  const DF df;
  const D64 d64;
  const size_t half = hn::Lanes(d64);
  const V64 b[2] = {hn::LoadU(d64, base), hn::LoadU(d64, base + half)};
  VF v[6];
  if (sobol) {
    const VU reversed = hn::LoadU(DU(), reversedIndex);
    Sobol3D(b, reversed, 3, v[0], v[1], v[2]);
    Sobol3D(b, reversed, 6, v[3], v[4], v[5]);
  } else {
    for (int j = 0; j < 6; ++j) v[j] = Independent(b, uint64_t(j + 1));
  }
  hn::StoreInterleaved3(v[0], v[1], v[2], df, &first->x);
  hn::StoreInterleaved3(v[3], v[4], v[5], df, &second->x);
}

void DrawTwo3D(int32_t sobol, size_t n, const uint64_t* base, const uint32_t* reversedIndex,
               Vec3* first, Vec3* second) {
  const size_t lanes = hn::Lanes(DF());
  // The inputs and outputs have room for whole vectors (SamplerDrawsAhead::resize): the last
  // partial vector reads its padding and writes past n.
  for (size_t k = 0; k < n; k += lanes)
    Block(sobol, base + k, reversedIndex + k, first + k, second + k);
}

#endif  // HWY_TARGET != HWY_SCALAR
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(DrawTwo3D);

void SamplerDrawsAhead::resize(size_t n) {
  const size_t padded = wholeSimdVectors(n);
  if (base.size() >= padded) return;  // grown once, kept from call to call
  first.resize(padded), second.resize(padded);
  base.resize(padded), reversedIndex.resize(padded);
}

void SamplerBatch::drawTwo3D(Sampler::Sequence sequence, const Sampler* samplers,
                             const uint32_t* index, size_t n, SamplerDrawsAhead& out) {
  out.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const Sampler& s = samplers[index[k]];
    out.base[k] = s.drawBase(), out.reversedIndex[k] = s.reversedIndex();
  }
  HWY_DYNAMIC_DISPATCH(DrawTwo3D)
  (sequence == Sampler::Sequence::kSobol, n, out.base.data(), out.reversedIndex.data(),
   out.first.data(), out.second.data());
}

}  // namespace tray
#endif  // HWY_ONCE

// Highway's dynamic dispatch, as integrators/camera_batch.cpp: compiled once per x86 target.
// Integer hashes and one exact int-to-float conversion per value: the same bits on every target.
// The draws are not written here: they are the one text of core/sampler_lanes.h, which Sampler runs
// with scalar integers, compiled here for each target's vectors (docs/lanes.md).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/sampler_batch.cpp"
#include "integrators/sampler_batch.h"

#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: the SIMD lane, then the one text for its vectors.
#include "core/lane_simd-inl.h"
#define TRAY_LANES_SIMD
#include "core/sampler_lanes.h"
#undef TRAY_LANES_SIMD

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// Without a SIMD target (hasSimdTarget) the wavefront draws as it goes: never called.
void DrawTwo3D(int32_t, size_t, const uint64_t*, const uint32_t*, Vec3*, Vec3*) {}
#else
static_assert(HWY_MAX_BYTES / sizeof(float) <= kMaxSimdLanes);

/// One vector of samplers from entry k: their next two 3D draws (Sampler::next3D, the hashes of
/// dimensions 3 and 6 on from the draw base), as Vec3s (x, y, z interleaved) at first + k and
/// second + k.
HWY_INLINE void Block(int32_t sobol, const uint64_t* base, const uint32_t* reversedIndex,
                      Vec3* first, Vec3* second) {
  const DF df;
  const D64 d64;
  const U64Vec b(hn::LoadU(d64, base), hn::LoadU(d64, base + hn::Lanes(d64)));
  Vec3Vec v[2];
  if (sobol) {
    const UintVec reversed = hn::LoadU(DU(), reversedIndex);
    for (int d = 0; d < 2; ++d)
      v[d] = sobol3DOf<FloatVec>(dimensionHashOf(b, 3u * (d + 1)), reversed);
  } else {
    // Independent: three next1D() values in order.
    for (int d = 0; d < 2; ++d) {
      FloatVec c[3];
      for (int j = 0; j < 3; ++j)
        c[j] = independentUnitOf<FloatVec>(dimensionHashOf(b, uint64_t(3 * d + j + 1)));
      v[d] = {c[0], c[1], c[2]};
    }
  }
  hn::StoreInterleaved3(v[0].x.v, v[0].y.v, v[0].z.v, df, &first->x);
  hn::StoreInterleaved3(v[1].x.v, v[1].y.v, v[1].z.v, df, &second->x);
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

// Highway's dynamic dispatch, as integrators/surface_batch.cpp: the transposition of eight of TRay's
// rays (array of structures) into Embree's 8-ray packet (structure of arrays), a field of eight
// rays per store instead of a store per field and ray: by an 8 x 8 transpose in registers on
// AVX2 and AVX-512, by gathers on the 128-bit targets. Copies only: the same bits as toLane in
// accel/embree_batch.cpp.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "accel/embree_pack.cpp"
#include "accel/embree_pack.h"

#include <cstddef>

#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Ray's fields as 4-byte words: o (0-2), d (3-5), tmin (6), tmax (7), blend (8), time (9).
static_assert(sizeof(Ray) == 40 && offsetof(Ray, o) == 0 && offsetof(Ray, d) == 12 &&
              offsetof(Ray, tmin) == 24 && offsetof(Ray, tmax) == 28 && offsetof(Ray, time) == 36);
constexpr int kRayWords = 10;

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
/// Words 0-7 of the eight rays (origin, direction, tnear, tfar) by an 8 x 8 transpose in
/// registers: one 32-byte load per ray, three rounds of shuffles, one store per field. The
/// gathers it replaces (one per field) cost far more time than instructions on this project's
/// AMD EPYC host: perf put 3.6% of the Cornell box's render on them for 0.7% of its
/// instructions, and 1.0% on the transpose (docs/wavefront.md, "Gathers and cache lines").
void TransposeRays8(const float* base, float* const fields[8]) {
  const hn::Full256<float> d;
  const hn::Repartition<double, decltype(d)> dd;
  hn::Vec256<float> r[8], t[8], u[8];
  for (int k = 0; k < 8; ++k) r[k] = hn::LoadU(d, base + k * kRayWords);
  // Within each 128-bit half: rays k and k + 1 word by word ([a0 b0 a1 b1 | a4 b4 a5 b5], ...).
  for (int k = 0; k < 8; k += 2) {
    t[k] = hn::InterleaveLower(d, r[k], r[k + 1]);
    t[k + 1] = hn::InterleaveUpper(d, r[k], r[k + 1]);
  }
  // Then pairs of words: [a0 b0 c0 d0 | a4 b4 c4 d4], [a1 b1 c1 d1 | a5 b5 c5 d5], ...
  for (int k = 0; k < 8; k += 4) {
    for (int h = 0; h < 2; ++h) {
      const auto lo = hn::BitCast(dd, t[k + h]), hi = hn::BitCast(dd, t[k + h + 2]);
      u[k + 2 * h] = hn::BitCast(d, hn::InterleaveLower(dd, lo, hi));
      u[k + 2 * h + 1] = hn::BitCast(d, hn::InterleaveUpper(dd, lo, hi));
    }
  }
  // Then halves: rays 0-3 below, 4-7 above; word w in u[w % 4] (w < 4 low halves, else high).
  for (int w = 0; w < 4; ++w) {
    hn::StoreU(hn::ConcatLowerLower(d, u[4 + w], u[w]), d, fields[w]);
    hn::StoreU(hn::ConcatUpperUpper(d, u[4 + w], u[w]), d, fields[w + 4]);
  }
}
#endif

bool PackRays8(const Ray* rays, uint32_t firstId, RTCRay8& p) {
  const hn::CappedTag<float, 8> df;
  const hn::RebindToUnsigned<decltype(df)> du;
  const float* base = &rays[0].o.x;
  // The packet's fields in Ray's word order; tfar before time (word 8 is blend: not Embree's).
  float* fields[] = {p.org_x, p.org_y, p.org_z, p.dir_x, p.dir_y, p.dir_z, p.tnear, p.tfar};
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
  TransposeRays8(base, fields);
  for (int k = 0; k < 8; ++k) p.time[k] = rays[k].time;
#else
  const hn::RebindToSigned<decltype(df)> di;
  for (size_t l = 0; l < 8; l += hn::Lanes(df)) {
    // Lane k reads ray l + k: word w at (l + k) * kRayWords + w.
    const auto row = hn::Mul(hn::Iota(di, int32_t(l)), hn::Set(di, kRayWords));
    for (int w = 0; w < 8; ++w) hn::StoreU(hn::GatherIndex(df, base + w, row), df, fields[w] + l);
    hn::StoreU(hn::GatherIndex(df, base + 9, row), df, p.time + l);
  }
#endif
  // embreeAccepts (accel/embree_rays.h) for the eight at once, from the packet's fields: every
  // origin and direction coordinate within FLT_LARGE (false for NaN), t not NaN.
  const auto large = hn::Set(df, 1.844e18f);
  auto accepted = hn::Eq(hn::Zero(df), hn::Zero(df));
  for (size_t l = 0; l < 8; l += hn::Lanes(df)) {
    hn::StoreU(hn::Set(du, 0xffffffffu), du, p.mask + l);
    hn::StoreU(hn::Iota(du, firstId + uint32_t(l)), du, p.id + l);
    hn::StoreU(hn::Zero(du), du, p.flags + l);
    for (int w = 0; w < 6; ++w)
      accepted = hn::And(accepted, hn::Le(hn::Abs(hn::LoadU(df, fields[w] + l)), large));
    for (int w = 6; w < 8; ++w) {
      const auto t = hn::LoadU(df, fields[w] + l);
      accepted = hn::And(accepted, hn::Eq(t, t));
    }
  }
  return hn::AllTrue(df, accepted);
}

}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(PackRays8);

bool packRays8(const Ray* rays, uint32_t firstId, RTCRay8& packet) {
  return HWY_DYNAMIC_DISPATCH(PackRays8)(rays, firstId, packet);
}

}  // namespace tray
#endif  // HWY_ONCE

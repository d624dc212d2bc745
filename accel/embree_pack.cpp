// Highway's dynamic dispatch, as core/surface_batch.cpp: the transposition of eight of TRay's
// rays (array of structures) into Embree's 8-ray packet (structure of arrays) by gathers, a
// field of eight rays per instruction instead of a store per field and ray. Copies only: the
// same bits as toLane in accel/embree_batch.cpp.
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

void PackRays8(const Ray* rays, uint32_t firstId, RTCRay8& p) {
  const hn::CappedTag<float, 8> df;
  const hn::RebindToSigned<decltype(df)> di;
  const hn::RebindToUnsigned<decltype(df)> du;
  const float* base = &rays[0].o.x;
  // The packet's fields in Ray's word order; tfar before time (word 8 is blend: not Embree's).
  float* fields[] = {p.org_x, p.org_y, p.org_z, p.dir_x, p.dir_y, p.dir_z, p.tnear, p.tfar};
  for (size_t l = 0; l < 8; l += hn::Lanes(df)) {
    // Lane k reads ray l + k: word w at (l + k) * kRayWords + w.
    const auto row = hn::Mul(hn::Iota(di, int32_t(l)), hn::Set(di, kRayWords));
    for (int w = 0; w < 8; ++w) hn::StoreU(hn::GatherIndex(df, base + w, row), df, fields[w] + l);
    hn::StoreU(hn::GatherIndex(df, base + 9, row), df, p.time + l);
    hn::StoreU(hn::Set(du, 0xffffffffu), du, p.mask + l);
    hn::StoreU(hn::Iota(du, firstId + uint32_t(l)), du, p.id + l);
    hn::StoreU(hn::Zero(du), du, p.flags + l);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(PackRays8);

void packRays8(const Ray* rays, uint32_t firstId, RTCRay8& packet) {
  HWY_DYNAMIC_DISPATCH(PackRays8)(rays, firstId, packet);
}

}  // namespace tray
#endif  // HWY_ONCE

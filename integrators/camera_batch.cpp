// Highway's dynamic dispatch: this file is compiled once per x86 target (SSSE3 ... AVX-512) by
// foreach_target.h, and HWY_DYNAMIC_DISPATCH runs the best one the CPU has. The samplers, pixel
// offsets and rays are not written here: they are the one text of core/sampler_lanes.h,
// core/pixel_sampler_lanes.h and core/camera_lanes.h, which Sampler, PixelSampler::offset and
// PerspectiveCamera::generateRay run with scalars, compiled here for each target's vectors
// (docs/lanes.md).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/camera_batch.cpp"
#include "integrators/camera_batch.h"

#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: the SIMD lane, then the one text for its vectors.
#include "core/lane_simd-inl.h"
#define TRAY_LANES_SIMD
#include "core/camera_lanes.h"
#include "core/pixel_sampler_lanes.h"
#include "core/sampler_lanes.h"
#undef TRAY_LANES_SIMD

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// One lane has no halves to pair: CameraRayBatch::make leaves CPUs with no SIMD target to the
// scalar code, so this is never called.
void GenerateCameraRays(const CameraBatchParams&, size_t, const int32_t*, const int32_t*,
                        const uint32_t*, CameraRayLanes&) {}
#else
static_assert(HWY_MAX_BYTES / sizeof(float) <= CameraRayLanes::kMaxLanes);

/// The samplers of one vector of samples: Sampler's constructor, then next2D. Writes the keys
/// and reversed indices; returns the 2D point.
HWY_INLINE Vec2Vec SamplersAndPoints(const CameraBatchParams& p, UintVec pixel, UintVec sample,
                                     uint64_t* key, uint32_t* reversedIndex) {
  const D64 d64;
  const U64Vec k = samplerKeyOf<FloatVec>(p.seedKey, pixel, sample, p.sobol != 0);
  hn::StoreU(k.lo, d64, key);
  hn::StoreU(k.hi, d64, key + hn::Lanes(d64));
  const UintVec reversed = reverseBitsOf(sample);
  hn::StoreU(reversed.v, DU(), reversedIndex);
  // Sobol': next2D at dimension 2. Independent: next1D twice, dimensions 1 and 2.
  if (p.sobol) return sobol2DOf<FloatVec>(dimensionHashOf(k, 2), reversed);
  return {independentUnitOf<FloatVec>(dimensionHashOf(k, 1)),
          independentUnitOf<FloatVec>(dimensionHashOf(k, 2))};
}

/// One vector of paths: samplers, offsets (pixelOffset), then the pinhole rays (pinholeRay).
/// Reads lanes from x, y, sample; writes them at entry k of out.
HWY_INLINE void Block(const CameraBatchParams& p, const int32_t* x, const int32_t* y,
                      const uint32_t* sample, size_t k, CameraRayLanes& out) {
  const DF df;
  const DI di;
  const DU du;
  const auto xi = hn::LoadU(di, x), yi = hn::LoadU(di, y);
  const UintVec s = hn::LoadU(du, sample);
  const UintVec pixel =
      UintVec(hn::BitCast(du, yi)) * UintVec(p.imageWidth) + UintVec(hn::BitCast(du, xi));
  const Vec2Vec u =
      SamplersAndPoints(p, pixel, s, out.key.data() + k, out.reversedIndex.data() + k);
  // Named with the namespace: PixelSampler's own (tray) holds the scalar template too.
  const Vec2Vec o = HWY_NAMESPACE::pixelOffset<FloatVec>(p.pixels, intFromBits(s), u);
  hn::StoreU(o.x.v, df, out.offsetX.data() + k);
  hn::StoreU(o.y.v, df, out.offsetY.data() + k);
  const FloatVec rx = rasterCoordinate(toFloatOf(IntVec(xi)), o.x);
  const FloatVec ry = rasterCoordinate(toFloatOf(IntVec(yi)), o.y);
  Vec3Vec d;
  FloatVec tmin;
  pinholeRay(p.toWorld, perspectiveDirection(rx, ry, p.width, p.height, p.tanHalfX, p.tanHalfY),
             p.znear, d, tmin);
  hn::StoreU(d.x.v, df, out.dirX.data() + k);
  hn::StoreU(d.y.v, df, out.dirY.data() + k);
  hn::StoreU(d.z.v, df, out.dirZ.data() + k);
  hn::StoreU(tmin.v, df, out.tmin.data() + k);
}

void GenerateCameraRays(const CameraBatchParams& p, size_t n, const int32_t* x, const int32_t* y,
                        const uint32_t* sample, CameraRayLanes& out) {
  const size_t lanes = hn::Lanes(DF());
  size_t k = 0;
  for (; k + lanes <= n; k += lanes) Block(p, x + k, y + k, sample + k, k, out);
  if (k == n) return;
  // The last partial vector: padded inputs, and the lanes that exist copied out (out has room
  // for whole vectors, CameraRayLanes::resize).
  int32_t xs[CameraRayLanes::kMaxLanes] = {}, ys[CameraRayLanes::kMaxLanes] = {};
  uint32_t ss[CameraRayLanes::kMaxLanes] = {};
  for (size_t j = k; j < n; ++j) xs[j - k] = x[j], ys[j - k] = y[j], ss[j - k] = sample[j];
  Block(p, xs, ys, ss, k, out);
}

#endif  // HWY_TARGET != HWY_SCALAR
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(GenerateCameraRays);

void CameraRayLanes::resize(size_t n) {
  // Whole vectors of the widest target: the kernel's last store may run past n.
  const size_t padded = wholeSimdVectors(n);
  if (key.size() >= padded) return;  // grown once, kept from call to call
  key.resize(padded), reversedIndex.resize(padded);
  offsetX.resize(padded), offsetY.resize(padded);
  dirX.resize(padded), dirY.resize(padded), dirZ.resize(padded), tmin.resize(padded);
}

std::optional<CameraRayBatch> CameraRayBatch::make(const Camera& camera, const PixelSampler& pixels,
                                                   uint64_t seed, Sampler::Sequence sequence,
                                                   bool moving, int imageWidth) {
  const std::optional<PinholeProjection> pinhole = camera.pinhole();
  if (!pinhole || moving) return std::nullopt;
  if (!hasSimdTarget()) return std::nullopt;
  CameraRayBatch b;
  CameraBatchParams& p = b.params_;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) p.toWorld[r][c] = pinhole->toWorld.m.m[r][c];
  p.width = pinhole->width, p.height = pinhole->height, p.znear = pinhole->znear;
  p.tanHalfX = pinhole->tanHalfX, p.tanHalfY = pinhole->tanHalfY;
  p.pixels = pixels;
  p.sobol = sequence == Sampler::Sequence::kSobol;
  p.imageWidth = uint32_t(imageWidth);
  p.seedKey = Sampler::seedKey(seed);
  b.origin_ = pinhole->toWorld.point(Vec3(0.0f));
  b.sequence_ = sequence;
  return b;
}

void CameraRayBatch::generate(size_t n, const int32_t* x, const int32_t* y, const uint32_t* sample,
                              CameraRayLanes& out) const {
  out.resize(n);
  HWY_DYNAMIC_DISPATCH(GenerateCameraRays)(params_, n, x, y, sample, out);
}

}  // namespace tray
#endif  // HWY_ONCE

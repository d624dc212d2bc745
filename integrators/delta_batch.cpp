// Highway's dynamic dispatch, as integrators/glossy_batch.cpp: compiled once per x86 target,
// with -ffp-contract=off (as the whole project). Each lane runs PathEstimator::step's second
// half for smooth glass from the same text the scalar code runs (materials/dielectric_lanes.h,
// included by integrators/shading_simd-inl.h): the frame, sampleSmoothDielectric, the lone
// lobe's pdf check (Bsdf::sampleLocal), the throughput and the next ray.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/delta_batch.cpp"
#include "integrators/delta_batch.h"

#include "core/simd_lanes.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: the lane types and the stages' shared plumbing.
#include "integrators/shading_simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {

#if HWY_TARGET == HWY_SCALAR
// DeltaBatch::useful() is false without a SIMD target: never called.
void DeltaVertices(ShadingLanes&) {}
#else

void DeltaVertices(ShadingLanes& lanes) {
  const size_t n = hn::Lanes(DF());
  // Whole vectors: the inputs are padded (ShadingLanes::padInputs), and the outputs have room.
  for (size_t q = 0; q < lanes.count; q += n) {
    const Fields f{lanes, q};
    const FrameOf<V3> frame = FrameOf<V3>::fromNormal(f.load(f.m.n));
    const DeltaSampleOf<V3> s = sampleSmoothDielectric(
        frame.toLocal(f.load(f.m.wo)), f.load(f.m.eta), f.load(f.m.albedo), f.load(f.m.lobeDraw));
    // A lone lobe's sample keeps a pdf that is positive and finite (Bsdf::sampleLocal).
    const FloatVec pdf = select(s.pdf > 0.0f && isFiniteOf(s.pdf), s.pdf, FloatVec(0.0f));
    StoreNextRay(f, s.f, frame.toWorld(s.wi), frame.n, pdf);
    f.store(f.m.etaScale, s.etaScale);
    f.store(f.m.transmitted, maskBits(s.transmission));
  }
}

#endif  // HWY_TARGET != HWY_SCALAR
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(DeltaVertices);

DeltaBatch::DeltaBatch() : useful_(hasSimdTarget()) {}

void DeltaBatch::compute(ShadingLanes& lanes) const {
  if (lanes.count == 0) return;
  lanes.padInputs();
  HWY_DYNAMIC_DISPATCH(DeltaVertices)(lanes);
}

}  // namespace tray
#endif  // HWY_ONCE

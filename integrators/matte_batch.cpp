// Highway's dynamic dispatch, as integrators/surface_batch.cpp: compiled once per x86 target, with
// -ffp-contract=off (as the whole project). Each lane runs PathEstimator::step's second half
// for a lone Lambert lobe and a triangle light or the constant environment, from the same text
// the scalar code runs (the *_lanes.h files, included by integrators/shading_simd-inl.h), so
// the bits are the same: the light sample, lambertEvalPdf, powerHeuristic and the shadow ray;
// lambertSample in the frame of n, the throughput and the next ray.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/matte_batch.cpp"
#include "integrators/matte_batch.h"

#include "core/simd_lanes.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: the lane types and the stages' shared plumbing.
#include "integrators/shading_simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {

#if HWY_TARGET == HWY_SCALAR
// MatteBatch::useful() is false without a SIMD target: never called.
void MatteVertices(const EmitterTables&, ShadingLanes&) {}
#else

/// Next-event estimation of one vector of vertices, as nextEvent runs it for a Lambert lobe
/// (Bsdf::lambertEval: the cosines to n alone).
template <bool kEnvironment>
HWY_NOINLINE void LightSample(const Fields& f, const EmitterTables& tables) {
  const V3 p = f.load(f.m.p), ng = f.load(f.m.ng), n = f.load(f.m.n);
  const ChosenLightSample ls = SampleChosenLight<kEnvironment>(f, tables, p, n);
  const FloatVec cosI = dot(ls.wi, n);
  FloatVec bsdfPdf;
  const V3 fr =
      lambertEvalPdf(f.load(f.m.albedo), dot(f.load(f.m.wo), n), cosI, bsdfPdf) * absOf(cosI);
  StoreLightSample(f, ls, fr, bsdfPdf, p, ng);
}

/// BSDF sampling of one vector of vertices, as Bsdf::lambertSample: the cosine lobe on wo's
/// side of n, placed in the frame of n.
HWY_NOINLINE void ScatterSample(const Fields& f) {
  const V3 n = f.load(f.m.n);
  const LambertSampleOf<V3> s =
      lambertSample(f.load(f.m.albedo), dot(f.load(f.m.wo), n), f.load(f.m.bsdfDraw));
  StoreNextRay(f, s.f, FrameOf<V3>::fromNormal(n).toWorld(s.wi), n, s.pdf);
}

void MatteVertices(const EmitterTables& tables, ShadingLanes& lanes) {
  const size_t n = hn::Lanes(DF());
  // Whole vectors: the inputs are padded (ShadingLanes::padInputs), and the outputs have room.
  for (size_t q = 0; q < lanes.count; q += n) {
    const Fields f{lanes, q};
    if (noneOf(EnvironmentLanes(f)))
      LightSample<false>(f, tables);
    else
      LightSample<true>(f, tables);
    ScatterSample(f);
  }
}

#endif  // HWY_TARGET != HWY_SCALAR
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(MatteVertices);

MatteBatch::MatteBatch(const LightSet& lights)
    : choices_(lights.size(), kOtherLight), triangleSampling_(lights.triangleSampling()) {
  for (size_t i = 0; i < lights.size(); ++i) {
    const AreaLight* area = lights.areaLight(i);
    if (!area || !(area->isTriangle() || area->isRectangle())) continue;
    const AreaLight::Triangle t = area->triangleData();
    choices_[i] = int32_t(table_.size() / kColumnCount);
    // One line per group of Column.
    // clang-format off
    const float row[kColumnCount] = {t.p0.x, t.p0.y, t.p0.z, t.e1.x, t.e1.y, t.e1.z,
                                     t.e2.x, t.e2.y, t.e2.z, t.n.x, t.n.y, t.n.z,
                                     area->isRectangle() ? -t.area : t.area,
                                     t.Le.x, t.Le.y, t.Le.z, t.doubleSided ? 1.0f : 0.0f};
    // clang-format on
    table_.insert(table_.end(), row, row + kColumnCount);
  }
  for (size_t i = 0; i < lights.size(); ++i) {
    const PunctualLight* punctual = lights.punctualLight(i);
    if (!punctual) continue;
    const PunctualLightOf<Vec3>& l = punctual->lanes();
    choices_[i] = kFirstPunctual - int32_t(punctual_.size() / kPunctualColumnCount);
    // clang-format off
    const float row[kPunctualColumnCount] = {
        l.directional ? 1.0f : 0.0f, l.spot ? 1.0f : 0.0f,
        l.position.x, l.position.y, l.position.z, l.direction.x, l.direction.y, l.direction.z,
        l.intensity.x, l.intensity.y, l.intensity.z, l.cosOuter, l.cosInner};
    // clang-format on
    punctual_.insert(punctual_.end(), row, row + kPunctualColumnCount);
  }
  const int environment = lights.constantEnvironment();
  if (environment >= 0) {
    choices_[size_t(environment)] = kConstantEnvironment;
    environmentLe_ = lights.light(size_t(environment)).Le(Vec3(0.0f, 0.0f, 1.0f));
  }
  useful_ = hasSimdTarget() && (!table_.empty() || !punctual_.empty() || environment >= 0);
  // A row of zeros where there is no emissive triangle (no punctual light): what the lanes
  // gather when none of them chose one.
  if (table_.empty()) table_.assign(kColumnCount, 0.0f);
  if (punctual_.empty()) punctual_.assign(kPunctualColumnCount, 0.0f);
}

void MatteBatch::compute(ShadingLanes& lanes) const {
  if (lanes.count == 0) return;
  lanes.padInputs();
  HWY_DYNAMIC_DISPATCH(MatteVertices)(tables(), lanes);
}

}  // namespace tray
#endif  // HWY_ONCE

// Highway's dynamic dispatch, as core/surface_batch.cpp: compiled once per x86 target, with
// -ffp-contract=off (integrators/CMakeLists.txt). Every lane repeats PathEstimator::step's
// arithmetic for a lone Lambert lobe and a triangle light or the constant environment, term by
// term in its order (AreaLight::sampleTriangle, EnvironmentLight::sample, Bsdf::lambertEval and
// lambertSample, Frame::fromNormal, powerHeuristic, setSpawnRay and setSpawnRayTo), so the bits are
// the same. The concentric map's cosine and sine are core/sampling.h's polynomials, vectorised
// (SinCosQuarterPi).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/matte_batch.cpp"
#include "integrators/matte_batch.h"

#include <cmath>

#include "core/simd_lanes.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: Vec3 arithmetic over lanes, the stages' shared pieces.
#include "core/vec3_simd-inl.h"
#include "integrators/shading_simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// MatteBatch::useful() is false without a SIMD target: never called.
void MatteVertices(const float*, const Color&, ShadingLanes&) {}
#else

/// Next-event estimation of one vector of vertices: AreaLight::sampleTriangle or the constant
/// environment's sample (pdf times the choice's pmf), Bsdf::lambertEval, powerHeuristic and
/// the shadow ray, as nextEvent runs them.
template <bool kEnvironment>
HWY_NOINLINE void LightSample(const Fields& f, const float* table, const Color& environmentLe) {
  const DF df;
  const DI di;
  const VF zero = hn::Zero(df);
  const V3 p = f.load(f.m.p), ng = f.load(f.m.ng), n = f.load(f.m.n);
  const ChosenLightSample ls = SampleChosenLight<kEnvironment>(f, table, environmentLe, p, n);
  // Bsdf::lambertEval, times |cos| at the receiver.
  const VF cosO = Dot(f.load(f.m.wo), n), cosI = Dot(ls.wi, n);
  const MF same = hn::Gt(cosO * cosI, zero);
  const VF invPi = hn::Set(df, 1.0f / kPi);
  const VF bsdfPdf =
      hn::IfThenElseZero(same, hn::Div(StdMax(zero, hn::Abs(cosI)), hn::Set(df, kPi)));
  const VF absCos = hn::Abs(cosI);
  const V3 albedo = f.load(f.m.albedo);
  const V3 fr = {hn::IfThenElseZero(same, albedo.x * invPi) * absCos,
                 hn::IfThenElseZero(same, albedo.y * invPi) * absCos,
                 hn::IfThenElseZero(same, albedo.z * invPi) * absCos};
  const MF ok = hn::AndNot(Black(fr), ls.ok);
  // powerHeuristic(lightPdf, bsdfPdf), then beta f Le (w / pdf).
  const VF scale = hn::Div(PowerHeuristic(ls.pdf, bsdfPdf), ls.pdf);
  const V3 beta = f.load(f.m.beta);
  const V3& Le = ls.Le;
  f.store(f.m.contribution, {((beta.x * fr.x) * Le.x) * scale, ((beta.y * fr.y) * Le.y) * scale,
                             ((beta.z * fr.z) * Le.z) * scale});
  StoreShadowRay<kEnvironment>(f, ls, p, ng);
  f.store(f.m.lit, hn::VecFromMask(di, hn::RebindMask(di, ok)));
}

/// BSDF sampling of one vector of vertices: Bsdf::lambertSample (the concentric map, the
/// cosine-weighted direction in the frame of n), the throughput update and setSpawnRay.
HWY_NOINLINE void ScatterSample(const Fields& f) {
  const DF df;
  const VF zero = hn::Zero(df);
  // sampleUniformDiskConcentric, then sampleCosineHemisphere's z on wo's side.
  VF v1, v2, dx, dy;
  f.load(f.m.bsdfDraw, v1, v2);
  ConcentricDisk(v1, v2, dx, dy);
  const VF z = CosineZ(dx, dy);
  const V3 n = f.load(f.m.n);
  const VF woz = Dot(f.load(f.m.wo), n);
  const VF localZ = hn::IfThenElse(hn::Lt(woz, zero), hn::Neg(z), z);
  const VF pdf = hn::Div(StdMax(zero, hn::Abs(localZ)), hn::Set(df, kPi));
  const V3 wi = Basis(n).toWorld({dx, dy, localZ});
  // beta *= f (|cos| / pdf).
  const VF invPi = hn::Set(df, 1.0f / kPi);
  const VF s = hn::Div(hn::Abs(Dot(wi, n)), pdf);
  const V3 albedo = f.load(f.m.albedo), beta = f.load(f.m.beta);
  f.store(f.m.nextBeta, {beta.x * ((albedo.x * invPi) * s), beta.y * ((albedo.y * invPi) * s),
                         beta.z * ((albedo.z * invPi) * s)});
  StoreNextRay(f, wi, pdf);
}

void MatteVertices(const float* table, const Color& environmentLe, ShadingLanes& lanes) {
  const size_t n = hn::Lanes(DF());
  // Whole vectors: the inputs are padded (ShadingLanes::padInputs), and the outputs have room.
  for (size_t q = 0; q < lanes.count; q += n) {
    const Fields f{lanes, q};
    if (hn::AllFalse(DF(), EnvironmentLanes(f)))
      LightSample<false>(f, table, environmentLe);
    else
      LightSample<true>(f, table, environmentLe);
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

MatteBatch::MatteBatch(const LightSet& lights) : choices_(lights.size(), kOtherLight) {
  for (size_t i = 0; i < lights.size(); ++i) {
    const AreaLight* area = lights.areaLight(i);
    if (!area || !area->isTriangle()) continue;
    const AreaLight::Triangle t = area->triangleData();
    choices_[i] = int32_t(table_.size() / kColumnCount);
    // One line per group of Column.
    // clang-format off
    const float row[kColumnCount] = {t.p0.x, t.p0.y, t.p0.z, t.e1.x, t.e1.y, t.e1.z,
                                     t.e2.x, t.e2.y, t.e2.z, t.n.x, t.n.y, t.n.z,
                                     t.area, t.Le.x, t.Le.y, t.Le.z, t.doubleSided ? 1.0f : 0.0f};
    // clang-format on
    table_.insert(table_.end(), row, row + kColumnCount);
  }
  const int environment = lights.constantEnvironment();
  if (environment >= 0) {
    choices_[size_t(environment)] = kConstantEnvironment;
    environmentLe_ = lights.light(size_t(environment)).Le(Vec3(0.0f, 0.0f, 1.0f));
  }
  useful_ = hasSimdTarget() && (!table_.empty() || environment >= 0);
  // A row of zeros where there is no emissive triangle: what the lanes gather when none of
  // them chose one.
  if (table_.empty()) table_.assign(kColumnCount, 0.0f);
}

void MatteBatch::compute(ShadingLanes& lanes) const {
  if (lanes.count == 0) return;
  lanes.padInputs();
  HWY_DYNAMIC_DISPATCH(MatteVertices)(table_.data(), environmentLe_, lanes);
}

}  // namespace tray
#endif  // HWY_ONCE

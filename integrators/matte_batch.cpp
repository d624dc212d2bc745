// Highway's dynamic dispatch, as core/surface_batch.cpp: compiled once per x86 target, with
// -ffp-contract=off (integrators/CMakeLists.txt). Every lane repeats PathEstimator::step's
// arithmetic for a lone Lambert lobe and a triangle light, term by term in its order
// (AreaLight::sampleTriangle, Bsdf::lambertEval and lambertSample, Frame::fromNormal,
// powerHeuristic, setSpawnRay and setSpawnRayTo), so the bits are the same. The concentric
// map's cosine and sine are libm's, lane by lane, as the scalar code calls them.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/matte_batch.cpp"
#include "integrators/matte_batch.h"

#include <algorithm>
#include <cmath>

#include "core/simd_lanes.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: Vec3 arithmetic over lanes.
#include "core/vec3_simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// MatteBatch::useful() is false without a SIMD target: never called.
void MatteVertices(const float*, MatteLanes&) {}
#else
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;
using T = MatteBatch;

static_assert(HWY_MAX_BYTES / sizeof(float) <= kMaxSimdLanes);

/// One vector of the lanes, from entry q: Vec3 fields loaded and stored deinterleaved.
struct Fields {
  MatteLanes& m;
  size_t q;
  V3 load(const std::vector<Vec3>& v) const {
    V3 r;
    hn::LoadInterleaved3(DF(), &v[q].x, r.x, r.y, r.z);
    return r;
  }
  void load(const std::vector<Vec2>& v, VF& x, VF& y) const {
    hn::LoadInterleaved2(DF(), &v[q].x, x, y);
  }
  VF load(const std::vector<float>& v) const { return hn::LoadU(DF(), &v[q]); }
  void store(std::vector<Vec3>& v, const V3& a) const {
    hn::StoreInterleaved3(a.x, a.y, a.z, DF(), &v[q].x);
  }
  void store(std::vector<float>& v, VF a) const { hn::StoreU(a, DF(), &v[q]); }
  void store(std::vector<int32_t>& v, VI a) const { hn::StoreU(a, DI(), &v[q]); }
};

/// isBlack: every component == 0.
HWY_INLINE MF Black(const V3& c) {
  const DF df;
  const VF zero = hn::Zero(df);
  return hn::And(hn::And(hn::Eq(c.x, zero), hn::Eq(c.y, zero)), hn::Eq(c.z, zero));
}
/// std::max(a, b): b where a < b, else a (so NaN in b gives a, as the scalar code).
HWY_INLINE VF StdMax(VF a, VF b) {
  return hn::IfThenElse(hn::Lt(a, b), b, a);
}

/// offsetRayOrigin (core/ray.h) per component: a few ULPs along n, or a fixed step near 0.
HWY_INLINE VF OffsetOrigin(VF p, VF n) {
  const DF df;
  const DI di;
  const VI offset = hn::ConvertTo(di, hn::Mul(hn::Set(df, 256.0f), n));  // truncates, as C++
  const VI bits = hn::BitCast(di, p);
  const MF negative = hn::Lt(p, hn::Zero(df));
  const VI moved =
      hn::Add(bits, hn::IfThenElse(hn::RebindMask(di, negative), hn::Neg(offset), offset));
  const VF nearZero = hn::Add(p, hn::Mul(hn::Set(df, 1.0f / 65536.0f), n));
  return hn::IfThenElse(hn::Lt(hn::Abs(p), hn::Set(df, 1.0f / 32.0f)), nearZero,
                        hn::BitCast(df, moved));
}
/// setSpawnRay's and setSpawnRayTo's origin: p offset to the side of ng that `toward` goes.
HWY_INLINE V3 SpawnOrigin(const V3& p, const V3& ng, const V3& toward) {
  const DF df;
  const VF side =
      hn::IfThenElse(hn::Ge(Dot(toward, ng), hn::Zero(df)), hn::Set(df, 1.0f), hn::Set(df, -1.0f));
  const V3 n = Scale(ng, side);
  return {OffsetOrigin(p.x, n.x), OffsetOrigin(p.y, n.y), OffsetOrigin(p.z, n.z)};
}

/// Next-event estimation of one vector of vertices: AreaLight::sampleTriangle (pdf times the
/// choice's pmf), Bsdf::lambertEval, powerHeuristic and setSpawnRayTo, as nextEvent runs them.
HWY_NOINLINE void LightSample(const Fields& f, const float* table) {
  const DF df;
  const DI di;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const VI row = hn::LoadU(di, &f.m.emitter[f.q]);
  const MF chosen = hn::RebindMask(df, hn::Gt(row, hn::Set(di, -1)));
  const VI at = hn::Mul(hn::Max(row, hn::Zero(di)), hn::Set(di, T::kColumnCount));
  const auto column = [&](T::Column c) { return hn::GatherIndex(df, table + c, at); };
  const V3 p = f.load(f.m.p), ng = f.load(f.m.ng), n = f.load(f.m.n);
  // sampleUniformTriangle, then p0 + b1 e1 + b2 e2.
  VF u1, u2;
  f.load(f.m.lightDraw, u1, u2);
  const MF lower = hn::Lt(u1, u2);
  const VF half = hn::Div(hn::IfThenElse(lower, u1, u2), hn::Set(df, 2.0f));
  const VF b0 = hn::IfThenElse(lower, half, u1 - half);
  const VF b1 = hn::IfThenElse(lower, u2 - half, half);
  const VF b2 = (one - b0) - b1;
  const V3 target = {(column(T::kP0x) + b1 * column(T::kE1x)) + b2 * column(T::kE2x),
                     (column(T::kP0y) + b1 * column(T::kE1y)) + b2 * column(T::kE2y),
                     (column(T::kP0z) + b1 * column(T::kE1z)) + b2 * column(T::kE2z)};
  const V3 d = Sub(target, p);
  const VF dist2 = Dot(d, d);
  const V3 wi = Scale(d, one / hn::Sqrt(dist2));
  const V3 nLight = {column(T::kNx), column(T::kNy), column(T::kNz)};
  const VF cosL = hn::Neg(Dot(nLight, wi));
  const VF c = hn::Abs(cosL);
  const VF trianglePdf = hn::IfThenElseZero(hn::Gt(c, zero), hn::Div(dist2, c * column(T::kArea)));
  const VF lightPdf = trianglePdf * f.load(f.m.pmf);
  const MF faces = hn::Or(hn::Gt(column(T::kDoubleSided), zero), hn::Gt(cosL, zero));
  const V3 Le = {column(T::kLeR), column(T::kLeG), column(T::kLeB)};
  // Bsdf::lambertEval, times |cos| at the receiver.
  const VF cosO = Dot(f.load(f.m.wo), n), cosI = Dot(wi, n);
  const MF same = hn::Gt(cosO * cosI, zero);
  const VF invPi = hn::Set(df, 1.0f / kPi);
  const VF bsdfPdf =
      hn::IfThenElseZero(same, hn::Div(StdMax(zero, hn::Abs(cosI)), hn::Set(df, kPi)));
  const VF absCos = hn::Abs(cosI);
  const V3 albedo = f.load(f.m.albedo);
  const V3 fr = {hn::IfThenElseZero(same, albedo.x * invPi) * absCos,
                 hn::IfThenElseZero(same, albedo.y * invPi) * absCos,
                 hn::IfThenElseZero(same, albedo.z * invPi) * absCos};
  MF ok = hn::And(chosen, hn::Gt(dist2, zero));
  ok = hn::And(ok, faces);
  ok = hn::And(ok, hn::Gt(lightPdf, zero));
  ok = hn::AndNot(Black(Le), ok);
  ok = hn::AndNot(Black(fr), ok);
  // powerHeuristic(lightPdf, bsdfPdf), then beta f Le (w / pdf).
  const VF f2 = lightPdf * lightPdf, g2 = bsdfPdf * bsdfPdf;
  const VF sum = f2 + g2;
  VF w = hn::IfThenElseZero(hn::Gt(sum, zero), hn::Div(f2, sum));
  w = hn::IfThenElse(hn::IsInf(lightPdf), one, w);
  const VF scale = hn::Div(w, lightPdf);
  const V3 beta = f.load(f.m.beta);
  f.store(f.m.contribution, {((beta.x * fr.x) * Le.x) * scale, ((beta.y * fr.y) * Le.y) * scale,
                             ((beta.z * fr.z) * Le.z) * scale});
  // setSpawnRayTo(p, ng, target).
  const V3 origin = SpawnOrigin(p, ng, Sub(target, p));
  f.store(f.m.shadowOrigin, origin);
  f.store(f.m.shadowDir, Sub(target, origin));
  f.store(f.m.lit, hn::VecFromMask(di, hn::RebindMask(di, ok)));
}

/// BSDF sampling of one vector of vertices: Bsdf::lambertSample (the concentric map, the
/// cosine-weighted direction in the frame of n), the throughput update and setSpawnRay.
HWY_NOINLINE void ScatterSample(const Fields& f) {
  const DF df;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f), two = hn::Set(df, 2.0f);
  // sampleUniformDiskConcentric: both wedges' angles, one chosen.
  VF v1, v2;
  f.load(f.m.bsdfDraw, v1, v2);
  const VF ox = two * v1 - one, oy = two * v2 - one;
  const MF center = hn::And(hn::Eq(ox, zero), hn::Eq(oy, zero));
  const MF xWedge = hn::Gt(hn::Abs(ox), hn::Abs(oy));
  const VF r = hn::IfThenElse(xWedge, ox, oy);
  const VF quarter = hn::Set(df, kPi / 4.0f);
  const VF thetaX = quarter * hn::Div(oy, ox);
  const VF thetaY = hn::Set(df, kPi / 2.0f) - quarter * hn::Div(ox, oy);
  alignas(64) float theta[kMaxSimdLanes], cosine[kMaxSimdLanes], sine[kMaxSimdLanes];
  hn::Store(hn::IfThenElse(xWedge, thetaX, thetaY), df, theta);
  const size_t lanes = hn::Lanes(df);
  for (size_t k = 0; k < lanes; ++k) cosine[k] = std::cos(theta[k]), sine[k] = std::sin(theta[k]);
  const VF dx = hn::IfThenZeroElse(center, r * hn::Load(df, cosine));
  const VF dy = hn::IfThenZeroElse(center, r * hn::Load(df, sine));
  // sampleCosineHemisphere's z, on wo's side.
  const VF z = hn::Sqrt(StdMax(hn::Set(df, 0x1p-22f), (one - dx * dx) - dy * dy));
  const V3 n = f.load(f.m.n);
  const VF woz = Dot(f.load(f.m.wo), n);
  const VF localZ = hn::IfThenElse(hn::Lt(woz, zero), hn::Neg(z), z);
  const VF pdf = hn::Div(StdMax(zero, hn::Abs(localZ)), hn::Set(df, kPi));
  // Frame::fromNormal (orthonormalBasis), then toWorld.
  const VF sign = hn::CopySign(one, n.z);
  const VF a = hn::Div(hn::Set(df, -1.0f), sign + n.z);
  const VF bb = (n.x * n.y) * a;
  const V3 t = {one + ((sign * n.x) * n.x) * a, sign * bb, hn::Neg(sign) * n.x};
  const V3 b = {bb, sign + (n.y * n.y) * a, hn::Neg(n.y)};
  const V3 wi = {(dx * t.x + dy * b.x) + localZ * n.x, (dx * t.y + dy * b.y) + localZ * n.y,
                 (dx * t.z + dy * b.z) + localZ * n.z};
  // beta *= f (|cos| / pdf).
  const VF invPi = hn::Set(df, 1.0f / kPi);
  const VF s = hn::Div(hn::Abs(Dot(wi, n)), pdf);
  const V3 albedo = f.load(f.m.albedo), beta = f.load(f.m.beta);
  f.store(f.m.nextBeta, {beta.x * ((albedo.x * invPi) * s), beta.y * ((albedo.y * invPi) * s),
                         beta.z * ((albedo.z * invPi) * s)});
  f.store(f.m.pdf, pdf);
  f.store(f.m.rayOrigin, SpawnOrigin(f.load(f.m.p), f.load(f.m.ng), wi));
  f.store(f.m.rayDir, wi);
}

void MatteVertices(const float* table, MatteLanes& lanes) {
  const size_t n = hn::Lanes(DF());
  // Whole vectors: the inputs are padded (MatteLanes::padInputs), and the outputs have room.
  for (size_t q = 0; q < lanes.count; q += n) {
    const Fields f{lanes, q};
    LightSample(f, table);
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

void MatteLanes::reset(size_t size) {
  count = 0;
  const size_t padded = wholeSimdVectors(size);
  if (padded <= emitter.size()) return;
  for (std::vector<Vec3>* v : {&p, &ng, &n, &wo, &albedo, &beta, &shadowOrigin, &shadowDir,
                               &contribution, &rayOrigin, &rayDir, &nextBeta})
    v->resize(padded);
  lightDraw.resize(padded), bsdfDraw.resize(padded);
  pmf.resize(padded), emitter.resize(padded), pdf.resize(padded), lit.resize(padded);
  path.resize(padded), time.resize(padded), belowMatters.resize(padded);
}

void MatteLanes::padInputs() {
  const auto from = ptrdiff_t(count), to = ptrdiff_t(wholeSimdVectors(count));
  for (std::vector<Vec3>* v : {&p, &ng, &n, &wo, &albedo, &beta})
    std::fill(v->begin() + from, v->begin() + to, Vec3(0.0f));
  std::fill(lightDraw.begin() + from, lightDraw.begin() + to, Vec2{0.0f, 0.0f});
  std::fill(bsdfDraw.begin() + from, bsdfDraw.begin() + to, Vec2{0.0f, 0.0f});
  std::fill(pmf.begin() + from, pmf.begin() + to, 0.0f);
  std::fill(emitter.begin() + from, emitter.begin() + to, -1);
}

MatteBatch::MatteBatch(const LightSet& lights) : rows_(lights.size(), -1) {
  for (size_t i = 0; i < lights.size(); ++i) {
    const AreaLight* area = lights.areaLight(i);
    if (!area || !area->isTriangle()) continue;
    const AreaLight::Triangle t = area->triangleData();
    rows_[i] = int32_t(table_.size() / kColumnCount);
    // One line per group of Column.
    // clang-format off
    const float row[kColumnCount] = {t.p0.x, t.p0.y, t.p0.z, t.e1.x, t.e1.y, t.e1.z,
                                     t.e2.x, t.e2.y, t.e2.z, t.n.x, t.n.y, t.n.z,
                                     t.area, t.Le.x, t.Le.y, t.Le.z, t.doubleSided ? 1.0f : 0.0f};
    // clang-format on
    table_.insert(table_.end(), row, row + kColumnCount);
  }
  useful_ = hasSimdTarget() && !table_.empty();
}

void MatteBatch::compute(MatteLanes& lanes) const {
  if (lanes.count == 0) return;
  lanes.padInputs();
  HWY_DYNAMIC_DISPATCH(MatteVertices)(table_.data(), lanes);
}

}  // namespace tray
#endif  // HWY_ONCE

// SIMD pieces shared by the shading stages (integrators/matte_batch.cpp,
// integrators/glossy_batch.cpp): each is its scalar twin's operations in the same order, so
// that the stages give the scalar step's bits (they build with -ffp-contract=off). Highway's
// -inl.h convention: included once per target after hwy/highway.h and core/vec3_simd-inl.h,
// guarded per target by HWY_TARGET_TOGGLE.
#if defined(TRAY_INTEGRATORS_SHADING_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_INTEGRATORS_SHADING_SIMD_INL_H_
#undef TRAY_INTEGRATORS_SHADING_SIMD_INL_H_
#else
#define TRAY_INTEGRATORS_SHADING_SIMD_INL_H_
#endif

#include "core/sampling.h"
#include "core/simd_lanes.h"
#include "hwy/highway.h"
#include "integrators/matte_batch.h"
#include "integrators/shading_lanes.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET != HWY_SCALAR
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using MF = hn::Mask<DF>;

static_assert(HWY_MAX_BYTES / sizeof(float) <= kMaxSimdLanes);

/// One vector of the lanes, from entry q: Vec3 fields loaded and stored deinterleaved.
struct Fields {
  ShadingLanes& m;
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
  VI load(const std::vector<int32_t>& v) const { return hn::LoadU(DI(), &v[q]); }
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
/// std::min(a, b): b where b < a, else a.
HWY_INLINE VF StdMin(VF a, VF b) {
  return hn::IfThenElse(hn::Lt(b, a), b, a);
}
/// std::clamp(v, lo, hi) as libstdc++ writes it: std::min(std::max(v, lo), hi).
HWY_INLINE VF StdClamp(VF v, VF lo, VF hi) {
  return StdMin(StdMax(v, lo), hi);
}
/// a where m, else -a (a select of the sign, as `m ? a : -a`).
HWY_INLINE V3 NegateUnless(MF m, const V3& a) {
  return {hn::IfThenElse(m, a.x, hn::Neg(a.x)), hn::IfThenElse(m, a.y, hn::Neg(a.y)),
          hn::IfThenElse(m, a.z, hn::Neg(a.z))};
}
/// Per component select.
HWY_INLINE V3 Select(MF m, const V3& a, const V3& b) {
  return {hn::IfThenElse(m, a.x, b.x), hn::IfThenElse(m, a.y, b.y), hn::IfThenElse(m, a.z, b.z)};
}
/// normalize(a): a * (1 / length(a)), as core/math.h's Vec3 division.
HWY_INLINE V3 Normalize(const V3& a) {
  const DF df;
  return Scale(a, hn::Div(hn::Set(df, 1.0f), hn::Sqrt(Dot(a, a))));
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

/// Frame::fromNormal(n)'s tangents (orthonormalBasis, Duff et al. 2017).
struct Basis {
  V3 t, b, n;
  explicit Basis(const V3& normal) : n(normal) {
    const DF df;
    const VF one = hn::Set(df, 1.0f);
    const VF sign = hn::CopySign(one, n.z);
    const VF a = hn::Div(hn::Set(df, -1.0f), sign + n.z);
    const VF bb = (n.x * n.y) * a;
    t = {one + ((sign * n.x) * n.x) * a, sign * bb, hn::Neg(sign) * n.x};
    b = {bb, sign + (n.y * n.y) * a, hn::Neg(n.y)};
  }
  /// Frame::toLocal.
  V3 toLocal(const V3& v) const { return {Dot(v, t), Dot(v, b), Dot(v, n)}; }
  /// Frame::toWorld: (v.x t + v.y b) + v.z n.
  V3 toWorld(const V3& v) const {
    return {(v.x * t.x + v.y * b.x) + v.z * n.x, (v.x * t.y + v.y * b.y) + v.z * n.y,
            (v.x * t.z + v.y * b.z) + v.z * n.z};
  }
};

/// sinCosQuarterPi (core/sampling.h): the same polynomials, operation for operation.
HWY_INLINE void SinCosQuarterPi(VF t, VF& sine, VF& cosine) {
  const DF df;
  const VF t2 = t * t;
  const auto s = [&](int i) { return hn::Set(df, kSinQuarterPi[i]); };
  const auto c = [&](int i) { return hn::Set(df, kCosQuarterPi[i]); };
  sine = ((((s(4) * t2 + s(3)) * t2 + s(2)) * t2 + s(1)) * t2 + s(0)) * t;
  cosine = (((c(4) * t2 + c(3)) * t2 + c(2)) * t2 + c(1)) * t2 + c(0);
}
/// sampleUniformDiskConcentric(u1, u2): the point (dx, dy), (0, 0) at the centre.
HWY_INLINE void ConcentricDisk(VF u1, VF u2, VF& dx, VF& dy) {
  const DF df;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f), two = hn::Set(df, 2.0f);
  const VF ox = two * u1 - one, oy = two * u2 - one;
  const MF center = hn::And(hn::Eq(ox, zero), hn::Eq(oy, zero));
  const MF xWedge = hn::Gt(hn::Abs(ox), hn::Abs(oy));
  const VF r = hn::IfThenElse(xWedge, ox, oy);
  VF s, c;
  SinCosQuarterPi(hn::Div(hn::IfThenElse(xWedge, oy, ox), r), s, c);
  dx = hn::IfThenZeroElse(center, r * hn::IfThenElse(xWedge, c, s));
  dy = hn::IfThenZeroElse(center, r * hn::IfThenElse(xWedge, s, c));
}
/// sampleUniformDiskPolar(u1, u2): sqrt(u1) times cosSinTwoPi(u2).
HWY_INLINE void PolarDisk(VF u1, VF u2, VF& px, VF& py) {
  const DF df;
  const DI di;
  const VF four = hn::Set(df, 4.0f);
  const VF k = hn::Floor(four * u2 + hn::Set(df, 0.5f));
  VF s, c;
  SinCosQuarterPi(hn::Set(df, 2.0f) * (four * u2 - k), s, c);
  const VI quarter = hn::And(hn::ConvertTo(di, k), hn::Set(di, 3));
  const MF odd = hn::RebindMask(df, hn::Eq(hn::And(quarter, hn::Set(di, 1)), hn::Set(di, 1)));
  const MF negX =
      hn::RebindMask(df, hn::Or(hn::Eq(quarter, hn::Set(di, 1)), hn::Eq(quarter, hn::Set(di, 2))));
  const MF negY = hn::RebindMask(df, hn::Gt(quarter, hn::Set(di, 1)));
  const VF x = hn::IfThenElse(odd, s, c), y = hn::IfThenElse(odd, c, s);
  const VF r = hn::Sqrt(u1);
  px = r * hn::IfThenElse(negX, hn::Neg(x), x);
  py = r * hn::IfThenElse(negY, hn::Neg(y), y);
}
/// sampleCosineHemisphere's z from the disk point (dx, dy): floored at 2^-11.
HWY_INLINE VF CosineZ(VF dx, VF dy) {
  const DF df;
  return hn::Sqrt(StdMax(hn::Set(df, 0x1p-22f), (hn::Set(df, 1.0f) - dx * dx) - dy * dy));
}

/// AreaLight::sampleTriangle from MatteBatch's table for the lanes' chosen rows: the point,
/// the unit direction to it and the solid-angle pdf times the choice's pmf; `ok` where a
/// triangle was chosen and the sample is valid (the receiver is off the light's plane, the
/// light faces it, the pdf is positive, the radiance not black).
struct TriangleSample {
  V3 target, wi, Le;
  VF pdf;
  MF ok;
};
HWY_INLINE TriangleSample SampleTriangle(const Fields& f, const float* table, const V3& p) {
  using T = MatteBatch;
  const DF df;
  const DI di;
  const VF zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const VI row = f.load(f.m.emitter);
  const MF chosen = hn::RebindMask(df, hn::Gt(row, hn::Set(di, -1)));
  const VI at = hn::Mul(hn::Max(row, hn::Zero(di)), hn::Set(di, T::kColumnCount));
  const auto column = [&](T::Column c) { return hn::GatherIndex(df, table + c, at); };
  // sampleUniformTriangle, then p0 + b1 e1 + b2 e2.
  VF u1, u2;
  f.load(f.m.lightDraw, u1, u2);
  const MF lower = hn::Lt(u1, u2);
  const VF half = hn::Div(hn::IfThenElse(lower, u1, u2), hn::Set(df, 2.0f));
  const VF b0 = hn::IfThenElse(lower, half, u1 - half);
  const VF b1 = hn::IfThenElse(lower, u2 - half, half);
  const VF b2 = (one - b0) - b1;
  TriangleSample s;
  s.target = {(column(T::kP0x) + b1 * column(T::kE1x)) + b2 * column(T::kE2x),
              (column(T::kP0y) + b1 * column(T::kE1y)) + b2 * column(T::kE2y),
              (column(T::kP0z) + b1 * column(T::kE1z)) + b2 * column(T::kE2z)};
  const V3 d = Sub(s.target, p);
  const VF dist2 = Dot(d, d);
  s.wi = Scale(d, one / hn::Sqrt(dist2));
  const V3 nLight = {column(T::kNx), column(T::kNy), column(T::kNz)};
  const VF cosL = hn::Neg(Dot(nLight, s.wi));
  const VF c = hn::Abs(cosL);
  const VF trianglePdf = hn::IfThenElseZero(hn::Gt(c, zero), hn::Div(dist2, c * column(T::kArea)));
  s.pdf = trianglePdf * f.load(f.m.pmf);
  const MF faces = hn::Or(hn::Gt(column(T::kDoubleSided), zero), hn::Gt(cosL, zero));
  s.Le = {column(T::kLeR), column(T::kLeG), column(T::kLeB)};
  MF ok = hn::And(chosen, hn::Gt(dist2, zero));
  ok = hn::And(ok, faces);
  ok = hn::And(ok, hn::Gt(s.pdf, zero));
  s.ok = hn::AndNot(Black(s.Le), ok);
  return s;
}

/// The lanes' chosen light sampled: a triangle of the table (SampleTriangle), or the constant
/// environment as EnvironmentLight::sample draws it for a receiver that does not transmit
/// (the cosine lobe about n, normalised; pdf cosineHemispherePdf(n . wi) times the choice's
/// pmf). `ok` where a light was chosen and its sample is valid with some radiance.
struct ChosenLightSample {
  V3 wi, Le, target;  ///< target: the triangle's point (not for the environment)
  VF pdf;
  MF ok, environment;
};
/// The environment's lanes of s.
HWY_INLINE void SampleEnvironment(const Fields& f, const Color& environmentLe, const V3& n,
                                  ChosenLightSample& s) {
  const DF df;
  const VF zero = hn::Zero(df);
  VF u1, u2, dx, dy;
  f.load(f.m.lightDraw, u1, u2);
  ConcentricDisk(u1, u2, dx, dy);
  const V3 wi = Normalize(Basis(n).toWorld({dx, dy, CosineZ(dx, dy)}));
  const VF pdf = hn::Div(StdMax(zero, Dot(n, wi)), hn::Set(df, kPi)) * f.load(f.m.pmf);
  const V3 Le = {hn::Set(df, environmentLe.x), hn::Set(df, environmentLe.y),
                 hn::Set(df, environmentLe.z)};
  const MF ok = hn::AndNot(Black(Le), hn::Gt(pdf, zero));
  s.wi = Select(s.environment, wi, s.wi);
  s.Le = Select(s.environment, Le, s.Le);
  s.pdf = hn::IfThenElse(s.environment, pdf, s.pdf);
  s.ok = hn::Or(hn::AndNot(s.environment, s.ok), hn::And(s.environment, ok));
}
/// The lanes whose choice is the constant environment.
HWY_INLINE MF EnvironmentLanes(const Fields& f) {
  const DF df;
  const DI di;
  return hn::RebindMask(df, hn::Eq(f.load(f.m.emitter), hn::Set(di, kConstantEnvironment)));
}
/// kEnvironment: some lane chose the environment (EnvironmentLanes); the kernels instantiate
/// both, so that a vector of triangle choices alone runs the triangles' code without selects
/// (callgrind, Cornell box: the matte light sample spilled 60 more vector registers).
template <bool kEnvironment>
HWY_INLINE ChosenLightSample SampleChosenLight(const Fields& f, const float* table,
                                               const Color& environmentLe, const V3& p,
                                               const V3& n) {
  const DF df;
  const TriangleSample tri = SampleTriangle(f, table, p);
  ChosenLightSample s{tri.wi, tri.Le, tri.target, tri.pdf, tri.ok, hn::FirstN(df, 0)};
  if constexpr (kEnvironment) {
    s.environment = EnvironmentLanes(f);
    SampleEnvironment(f, environmentLe, n, s);
  }
  return s;
}
/// The shadow ray toward a chosen light's sample: setSpawnRay(p, ng, wi) toward the
/// environment (unbounded: finishDeferred sets tmax), setSpawnRayTo(p, ng, target) otherwise.
template <bool kEnvironment>
HWY_INLINE void StoreShadowRay(const Fields& f, const ChosenLightSample& ls, const V3& p,
                               const V3& ng) {
  if constexpr (!kEnvironment) {
    const V3 origin = SpawnOrigin(p, ng, Sub(ls.target, p));
    f.store(f.m.shadowOrigin, origin);
    f.store(f.m.shadowDir, Sub(ls.target, origin));
  } else {
    const V3 origin = SpawnOrigin(p, ng, Select(ls.environment, ls.wi, Sub(ls.target, p)));
    f.store(f.m.shadowOrigin, origin);
    f.store(f.m.shadowDir, Select(ls.environment, ls.wi, Sub(ls.target, origin)));
  }
}

/// The BSDF sample's pdf and setSpawnRay(p, ng, wi)'s origin and direction: the next ray.
HWY_INLINE void StoreNextRay(const Fields& f, const V3& wi, VF pdf) {
  f.store(f.m.pdf, pdf);
  f.store(f.m.rayOrigin, SpawnOrigin(f.load(f.m.p), f.load(f.m.ng), wi));
  f.store(f.m.rayDir, wi);
}

/// powerHeuristic(pf, pg) (core/sampling.h): 1 where pf is infinite.
HWY_INLINE VF PowerHeuristic(VF pf, VF pg) {
  const DF df;
  const VF f2 = pf * pf, g2 = pg * pg;
  const VF sum = f2 + g2;
  const VF w = hn::IfThenElseZero(hn::Gt(sum, hn::Zero(df)), hn::Div(f2, sum));
  return hn::IfThenElse(hn::IsInf(pf), hn::Set(df, 1.0f), w);
}
#endif  // HWY_TARGET != HWY_SCALAR

}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#endif  // TRAY_INTEGRATORS_SHADING_SIMD_INL_H_

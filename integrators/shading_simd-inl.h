// The SIMD shading stages' plumbing (integrators/matte_batch.cpp, glossy_batch.cpp,
// delta_batch.cpp): a vector of ShadingLanes' vertices loaded and stored, the chosen lights
// gathered from the emitter table and sampled, the shadow and next rays. The math is not here:
// it is the one text of the *_lanes.h files (warps, Fresnel, GGX, Lambert, the mixture, smooth
// glass, triangle lights, MIS), which this
// file includes in SIMD mode, so that the stages compile from what the scalar code runs
// (docs/lanes.md). Highway's -inl.h convention: included once per target after
// hwy/highway.h, guarded per target by HWY_TARGET_TOGGLE.
#if defined(TRAY_INTEGRATORS_SHADING_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_INTEGRATORS_SHADING_SIMD_INL_H_
#undef TRAY_INTEGRATORS_SHADING_SIMD_INL_H_
#else
#define TRAY_INTEGRATORS_SHADING_SIMD_INL_H_
#endif

#include "core/lane_simd-inl.h"
#include "core/simd_lanes.h"
#include "hwy/highway.h"
#include "integrators/matte_batch.h"
#include "integrators/shading_lanes.h"
// The one text, for this target's lanes.
#define TRAY_LANES_SIMD
#include "core/ray_lanes.h"
#include "core/sampling_lanes.h"
#include "core/spherical_rectangle_lanes.h"
#include "core/spherical_triangle_lanes.h"
#include "integrators/path_vertex_lanes.h"
#include "lights/punctual_light_lanes.h"
#include "lights/rectangle_light_lanes.h"
#include "lights/triangle_light_lanes.h"
#include "materials/dielectric_lanes.h"
#include "materials/ggx_mixture_lanes.h"
#include "materials/lambert_lanes.h"
#undef TRAY_LANES_SIMD

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {

#if HWY_TARGET != HWY_SCALAR
using V3 = Vec3Vec;
using V2 = Vec2Vec;

/// One vector of the lanes, from entry q: Vec3 fields loaded and stored deinterleaved.
struct Fields {
  ShadingLanes& m;
  size_t q;
  V3 load(const std::vector<Vec3>& v) const {
    hn::Vec<DF> x, y, z;
    hn::LoadInterleaved3(DF(), &v[q].x, x, y, z);
    return {x, y, z};
  }
  V2 load(const std::vector<Vec2>& v) const {
    hn::Vec<DF> x, y;
    hn::LoadInterleaved2(DF(), &v[q].x, x, y);
    return {x, y};
  }
  FloatVec load(const std::vector<float>& v) const { return hn::LoadU(DF(), &v[q]); }
  IntVec load(const std::vector<int32_t>& v) const { return hn::LoadU(DI(), &v[q]); }
  void store(std::vector<Vec3>& v, const V3& a) const {
    hn::StoreInterleaved3(a.x.v, a.y.v, a.z.v, DF(), &v[q].x);
  }
  void store(std::vector<float>& v, FloatVec a) const { hn::StoreU(a.v, DF(), &v[q]); }
  void store(std::vector<int32_t>& v, IntVec a) const { hn::StoreU(a.v, DI(), &v[q]); }
};

/// The lanes' chosen light sampled: a triangle of MatteBatch's table (sampleTriangleLight), a
/// punctual light of its punctual table (samplePunctualLight), or the constant environment as
/// EnvironmentLight::sample draws it for a receiver that does not transmit
/// (sampleCosineAbout). pdf: the sample's times the choice's pmf (a punctual light's 1 x pmf);
/// `ok` where a light was chosen and its sample is valid with some radiance
/// (LightSet::sampleChosen's checks); `delta` where it is a punctual light (no MIS);
/// `unbounded` where the shadow ray has no end (the environment, a directional light).
struct ChosenLightSample {
  V3 wi, Le, target;  ///< target: the triangle's or the point light's point (if bounded)
  FloatVec pdf;
  MaskVec ok, unbounded, delta;
};
/// Row `row` of a table of `columns` floats per row, per lane: one gather per column.
struct TableRows {
  const float* table;
  IntVec at;  ///< each lane's row start
  TableRows(const float* t, IntVec row, int32_t columns) : table(t), at(row * IntVec(columns)) {}
  FloatVec column(int c) const { return hn::GatherIndex(DF(), table + c, at.v); }
  V3 vec3(int x, int y, int z) const { return {column(x), column(y), column(z)}; }
};
/// A triangle row per lane (row 0 where none was chosen: its values are not used). Not inlined:
/// its 17 gathers inside the light sample made one straight block more than Valgrind's memcheck
/// can instrument ("VEX temporary storage exhausted", the glossy stage on DamagedHelmet); the
/// call ends a block, at a call's cost per vector (as integrators/surface_batch.cpp's Gather3).
inline HWY_NOINLINE TriangleLightOf<V3> GatherTriangles(const float* table, IntVec row, V3& Le) {
  using T = MatteBatch;
  const TableRows r(table, select(row > IntVec(-1), row, IntVec(0)), T::kColumnCount);
  Le = r.vec3(T::kLeR, T::kLeG, T::kLeB);
  return {r.vec3(T::kP0x, T::kP0y, T::kP0z),
          r.vec3(T::kE1x, T::kE1y, T::kE1z),
          r.vec3(T::kE2x, T::kE2y, T::kE2z),
          r.vec3(T::kNx, T::kNy, T::kNz),
          r.column(T::kArea),
          r.column(T::kDoubleSided) > 0.0f};
}
/// A punctual light's row per lane (row 0 where none was chosen: its values are not used), as
/// GatherTriangles and for the same reason out of line.
inline HWY_NOINLINE PunctualLightOf<V3> GatherPunctual(const float* table, IntVec code) {
  using T = MatteBatch;
  const MaskVec punctual = code < IntVec(kFirstPunctual + 1);
  const TableRows r(table, select(punctual, IntVec(kFirstPunctual) - code, IntVec(0)),
                    T::kPunctualColumnCount);
  PunctualLightOf<V3> l;
  l.directional = r.column(T::kDirectional) > 0.0f;
  l.spot = r.column(T::kSpot) > 0.0f;
  l.position = r.vec3(T::kPx, T::kPy, T::kPz);
  l.direction = r.vec3(T::kDx, T::kDy, T::kDz);
  l.intensity = r.vec3(T::kIr, T::kIg, T::kIb);
  l.cosOuter = r.column(T::kCosOuter), l.cosInner = r.column(T::kCosInner);
  return l;
}
/// A row's triangle (sampleTriangleLight) or rectangle (sampleRectangleLight, where the row's
/// area is negative: MatteBatch's table), each lane as the scalar AreaLight::sample would.
HWY_INLINE TriangleLightSampleOf<V3> SampleTriangleOrRectangle(TriangleLightOf<V3> l, const V3& p,
                                                               const V3& n, const V2& u,
                                                               const EmitterTables& tables) {
  const MaskVec rectangle = l.area < FloatVec(0.0f);
  if (noneOf(rectangle)) return sampleTriangleLight(l, p, n, u, tables.triangleSampling);
  l.area = absOf(l.area);
  const TriangleLightSampleOf<V3> r = sampleRectangleLight(l, p, n, u, tables.triangleSampling);
  if (allOf(rectangle)) return r;
  TriangleLightSampleOf<V3> t = sampleTriangleLight(l, p, n, u, tables.triangleSampling);
  t.p = select(rectangle, r.p, t.p), t.wi = select(rectangle, r.wi, t.wi);
  t.pdf = select(rectangle, r.pdf, t.pdf);
  t.valid = (rectangle && r.valid) || (!rectangle && t.valid);
  return t;
}

/// The lanes whose choice is the constant environment.
HWY_INLINE MaskVec EnvironmentLanes(const Fields& f) {
  return f.load(f.m.emitter) == IntVec(kConstantEnvironment);
}
/// kEnvironment: some lane chose the environment (EnvironmentLanes); the kernels instantiate
/// both, so that a vector of triangle choices alone runs the triangles' code without selects
/// (callgrind, Cornell box: the matte light sample spilled 60 more vector registers).
template <bool kEnvironment>
HWY_INLINE ChosenLightSample SampleChosenLight(const Fields& f, const EmitterTables& tables,
                                               const V3& p, const V3& n) {
  const IntVec row = f.load(f.m.emitter);
  const V2 u = f.load(f.m.lightDraw);
  const FloatVec pmf = f.load(f.m.pmf);
  ChosenLightSample s;
  const TriangleLightSampleOf<V3> t =
      SampleTriangleOrRectangle(GatherTriangles(tables.triangles, row, s.Le), p, n, u, tables);
  s.wi = t.wi, s.target = t.p, s.pdf = t.pdf * pmf;
  s.ok = row > IntVec(-1) && t.valid && s.pdf > 0.0f && !isBlack(s.Le);
  s.unbounded = MaskVec(false), s.delta = MaskVec(false);
  if constexpr (kEnvironment) {
    const MaskVec environment = EnvironmentLanes(f);
    const V3 wi = sampleCosineAbout(n, u);
    const FloatVec pdf = cosineHemispherePdf(dot(n, wi)) * pmf;
    const Color& e = tables.environmentLe;
    const V3 Le{e.x, e.y, e.z};
    const MaskVec ok = pdf > 0.0f && !isBlack(Le);
    s.wi = select(environment, wi, s.wi);
    s.Le = select(environment, Le, s.Le);
    s.pdf = select(environment, pdf, s.pdf);
    s.ok = (s.ok && !environment) || (environment && ok);
    s.unbounded = environment;
  }
  const MaskVec punctual = row < IntVec(kFirstPunctual + 1);
  if (anyOf(punctual)) {  // PunctualLight::sample: pdf 1, times the choice's pmf
    const PunctualLightOf<V3> l = GatherPunctual(tables.punctual, row);
    const PunctualLightSampleOf<V3> ps = samplePunctualLight(l, p);
    const FloatVec pdf = FloatVec(1.0f) * pmf;
    s.wi = select(punctual, ps.wi, s.wi);
    s.Le = select(punctual, ps.L, s.Le);
    s.target = select(punctual, l.position, s.target);
    s.pdf = select(punctual, pdf, s.pdf);
    s.ok = (punctual && ps.valid && pdf > 0.0f && !isBlack(ps.L)) || (!punctual && s.ok);
    s.unbounded = s.unbounded || (punctual && l.directional);
    s.delta = punctual;
  }
  return s;
}

/// The shadow ray toward a chosen light's sample: setSpawnRay(p, ng, wi) toward the
/// environment or a directional light (unbounded: finishDeferred sets tmax),
/// setSpawnRayTo(p, ng, target) otherwise.
HWY_INLINE void StoreShadowRay(const Fields& f, const ChosenLightSample& ls, const V3& p,
                               const V3& ng) {
  if (noneOf(ls.unbounded)) {  // no selects when every lane's ray ends at its light
    const V3 origin = spawnOrigin(p, ng, ls.target - p);
    f.store(f.m.shadowOrigin, origin);
    f.store(f.m.shadowDir, ls.target - origin);
  } else {
    const V3 origin = spawnOrigin(p, ng, select(ls.unbounded, ls.wi, ls.target - p));
    f.store(f.m.shadowOrigin, origin);
    f.store(f.m.shadowDir, select(ls.unbounded, ls.wi, ls.target - origin));
  }
  f.store(f.m.shadowUnbounded, maskBits(ls.unbounded));
}

/// Next-event estimation's outputs: the contribution (beta f Le, MIS-weighted), the shadow ray
/// and whether it is traced. fr: the BSDF toward the light times the cosine; bsdfPdf its pdf.
HWY_INLINE void StoreLightSample(const Fields& f, const ChosenLightSample& ls, const V3& fr,
                                 FloatVec bsdfPdf, const V3& p, const V3& ng) {
  // nextEvent's weight: 1 for a delta light, the power heuristic otherwise.
  const FloatVec w = select(ls.delta, FloatVec(1.0f), powerHeuristic(ls.pdf, bsdfPdf));
  f.store(f.m.contribution, neeContribution(f.load(f.m.beta), fr, ls.Le, w, ls.pdf));
  StoreShadowRay(f, ls, p, ng);
  f.store(f.m.lit, maskBits(ls.ok && !isBlack(fr)));
}

/// The BSDF sample's outputs (wi in world space): the throughput after it, its pdf (no sample
/// where 0) and setSpawnRay(p, ng, wi)'s origin and direction, the next ray.
HWY_INLINE void StoreNextRay(const Fields& f, const V3& fs, const V3& wi, const V3& n,
                             FloatVec pdf) {
  f.store(f.m.nextBeta, scatteredThroughput(f.load(f.m.beta), fs, wi, n, pdf));
  f.store(f.m.pdf, pdf);
  f.store(f.m.rayOrigin, spawnOrigin(f.load(f.m.p), f.load(f.m.ng), wi));
  f.store(f.m.rayDir, wi);
}
#endif  // HWY_TARGET != HWY_SCALAR

}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#endif  // TRAY_INTEGRATORS_SHADING_SIMD_INL_H_

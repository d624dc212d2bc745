// Highway's dynamic dispatch, as integrators/camera_batch.cpp: compiled once per x86 target, with
// -ffp-contract=off (core/CMakeLists.txt), as core/scene.cpp is: every lane's arithmetic is
// meshSurface's (core/scene.cpp), term by term in its order, so the bits are the same.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/surface_batch.cpp"
#include "integrators/surface_batch.h"

#include <cstddef>
#include <limits>

#include "core/simd_lanes.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: Vec3 arithmetic over lanes.
#include "integrators/vec3_simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// SurfaceBatch::useful() is false without a SIMD target: never called.
void SurfaceGroup(const SurfaceBatchPrimitive&, const int32_t*, size_t, const Hit*, const Ray*,
                  SurfacePoint*) {}
#else
using DF = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;

static_assert(HWY_MAX_BYTES / sizeof(float) <= kMaxSimdLanes);
static_assert(sizeof(Hit) % 4 == 0 && offsetof(Hit, triangle) % 4 == 0 &&
              offsetof(Hit, b1) % 4 == 0 && offsetof(Hit, b2) % 4 == 0);
static_assert(sizeof(Vec3) == 12 && sizeof(Vec2) == 8);

/// The three floats of Vec3 `index` in `base` (vertex arrays as floats). Not inlined: the
/// kernel as one straight block of gathers is more than Valgrind's memcheck can instrument
/// ("VEX temporary storage exhausted"; each call ends a block), at a call's cost per vector.
HWY_NOINLINE V3 Gather3(const float* base, VI index) {
  const DF df;
  const DI di;
  const VI i = index * hn::Set(di, 3);
  return {hn::GatherIndex(df, base, i), hn::GatherIndex(df, base + 1, i),
          hn::GatherIndex(df, base + 2, i)};
}

/// b0 a + b1 b + b2 c, componentwise, left to right (Vec3's operators).
HWY_INLINE VF Blend(VF b0, VF a, VF b1, VF b, VF b2, VF c) {
  return (b0 * a + b1 * b) + b2 * c;
}

/// Transform::normal: the inverse's columns, terms in order.
HWY_INLINE V3 Normal(const SurfaceBatchPrimitive& p, const V3& n) {
  const DF df;
  V3 r;
  VF* out[3] = {&r.x, &r.y, &r.z};
  for (int c = 0; c < 3; ++c)
    *out[c] = (hn::Set(df, p.inv[0][c]) * n.x + hn::Set(df, p.inv[1][c]) * n.y) +
              hn::Set(df, p.inv[2][c]) * n.z;
  return r;
}

/// The first `count` lanes of a group's vector (count <= lanes): meshSurface for each, then written
/// to out at the hit's own index, with Scene::surface's frontFace, time and primitive.
HWY_INLINE void Block(const SurfaceBatchPrimitive& p, const int32_t* order, size_t count,
                      const Hit* hits, const Ray* rays, SurfacePoint* out) {
  const DF df;
  const DI di;
  const VI j = hn::LoadU(di, order);
  const VI hitStride = j * hn::Set(di, int32_t(sizeof(Hit) / 4));
  const auto* hitInts = reinterpret_cast<const int32_t*>(hits);
  const auto* hitFloats = reinterpret_cast<const float*>(hits);
  const VI triangle = hn::GatherIndex(di, hitInts + offsetof(Hit, triangle) / 4, hitStride);
  const VF b1 = hn::GatherIndex(df, hitFloats + offsetof(Hit, b1) / 4, hitStride);
  const VF b2 = hn::GatherIndex(df, hitFloats + offsetof(Hit, b2) / 4, hitStride);
  const auto* indices = reinterpret_cast<const int32_t*>(p.indices);
  const VI corner = triangle * hn::Set(di, 3);
  const VI i0 = hn::GatherIndex(di, indices, corner);
  const VI i1 = hn::GatherIndex(di, indices + 1, corner);
  const VI i2 = hn::GatherIndex(di, indices + 2, corner);
  const VF one = hn::Set(df, 1.0f);
  const VF b0 = (one - b1) - b2;
  const V3 p0 = Gather3(p.positions, i0), p1 = Gather3(p.positions, i1),
           p2 = Gather3(p.positions, i2);
  // s.p = toWorld.point(b0 p0 + b1 p1 + b2 p2).
  const V3 local = {Blend(b0, p0.x, b1, p1.x, b2, p2.x), Blend(b0, p0.y, b1, p1.y, b2, p2.y),
                    Blend(b0, p0.z, b1, p1.z, b2, p2.z)};
  VF world[3];
  for (int r = 0; r < 3; ++r)
    world[r] = ((hn::Set(df, p.m[r][0]) * local.x + hn::Set(df, p.m[r][1]) * local.y) +
                hn::Set(df, p.m[r][2]) * local.z) +
               hn::Set(df, p.m[r][3]) * one;
  // ng = normalize(toWorld.normal(cross(p1 - p0, p2 - p0))); normalize is a * (1 / |a|).
  const V3 e1 = Sub(p1, p0), e2 = Sub(p2, p0);
  const V3 c = {e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x};
  const V3 ngw = Normal(p, c);
  const VF ngInverse = one / hn::Sqrt(Dot(ngw, ngw));
  const V3 ng = Scale(ngw, ngInverse);
  V3 n = ng, side = ng;
  if (p.hasNormals) {
    const V3 n0 = Gather3(p.normals, i0), n1 = Gather3(p.normals, i1), n2 = Gather3(p.normals, i2);
    const V3 nl = {Blend(b0, n0.x, b1, n1.x, b2, n2.x), Blend(b0, n0.y, b1, n1.y, b2, n2.y),
                   Blend(b0, n0.z, b1, n1.z, b2, n2.z)};
    const V3 nw = Normal(p, nl);
    const VF len = hn::Sqrt(Dot(nw, nw));
    // len > 0 && isfinite(len): a NaN fails both comparisons.
    const auto usable = hn::And(hn::Lt(hn::Zero(df), len),
                                hn::Lt(len, hn::Set(df, std::numeric_limits<float>::infinity())));
    const VF inverse = one / len;
    n = {hn::IfThenElse(usable, nw.x * inverse, ng.x), hn::IfThenElse(usable, nw.y * inverse, ng.y),
         hn::IfThenElse(usable, nw.z * inverse, ng.z)};
    const auto flip = hn::Lt(Dot(n, ng), hn::Zero(df));
    side = {hn::IfThenElse(flip, hn::Neg(ng.x), ng.x), hn::IfThenElse(flip, hn::Neg(ng.y), ng.y),
            hn::IfThenElse(flip, hn::Neg(ng.z), ng.z)};
  }
  VF u = b1, v = b2;
  if (p.hasUvs) {
    const VI i0u = i0 * hn::Set(di, 2), i1u = i1 * hn::Set(di, 2), i2u = i2 * hn::Set(di, 2);
    const float* uvs = p.uvs;
    u = Blend(b0, hn::GatherIndex(df, uvs, i0u), b1, hn::GatherIndex(df, uvs, i1u), b2,
              hn::GatherIndex(df, uvs, i2u));
    v = Blend(b0, hn::GatherIndex(df, uvs + 1, i0u), b1, hn::GatherIndex(df, uvs + 1, i1u), b2,
              hn::GatherIndex(df, uvs + 1, i2u));
  }
  // To the hits' own SurfacePoints, lane by lane.
  HWY_ALIGN float lanes[14][kMaxSimdLanes];
  const VF fields[14] = {world[0], world[1], world[2], side.x, side.y, side.z, n.x,
                         n.y,      n.z,      u,        v,      ng.x,   ng.y,   ng.z};
  for (int f = 0; f < 14; ++f) hn::Store(fields[f], df, lanes[f]);
  for (size_t l = 0; l < count; ++l) {
    const Hit& hit = hits[order[l]];
    const Ray& ray = rays[order[l]];
    SurfacePoint& s = out[order[l]];
    s.p = {lanes[0][l], lanes[1][l], lanes[2][l]};
    const Vec3 sideNormal{lanes[3][l], lanes[4][l], lanes[5][l]};
    s.ng = sideNormal;
    s.n = {lanes[6][l], lanes[7][l], lanes[8][l]};
    s.uv = {lanes[9][l], lanes[10][l]};
    s.material = hit.material >= 0 ? hit.material : p.material;
    s.primitive = hit.primitive;
    s.front = {lanes[11][l], lanes[12][l], lanes[13][l]};
    s.frontFace = dot(ray.d, sideNormal) < 0;
    s.time = ray.time;
  }
}

void SurfaceGroup(const SurfaceBatchPrimitive& p, const int32_t* order, size_t n, const Hit* hits,
                  const Ray* rays, SurfacePoint* out) {
  const size_t lanes = hn::Lanes(DF());
  size_t k = 0;
  for (; k + lanes <= n; k += lanes) Block(p, order + k, lanes, hits, rays, out);
  if (k == n) return;
  // The last partial vector: its missing lanes repeat the group's first hit (in bounds for
  // every gather), and are not written out.
  int32_t padded[kMaxSimdLanes];
  for (size_t l = 0; l < lanes; ++l) padded[l] = order[k + l < n ? k + l : 0];
  Block(p, padded, n - k, hits, rays, out);
}

#endif  // HWY_TARGET != HWY_SCALAR
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(SurfaceGroup);

SurfaceBatch::SurfaceBatch(const Scene& scene) : scene_(scene) {
  primitives_.resize(scene.primitives.size());
  batched_.assign(scene.primitives.size(), 0);
  const bool simd = hasSimdTarget();
  for (size_t i = 0; i < scene.primitives.size() && simd; ++i) {
    const Primitive& prim = scene.primitives[i];
    if (prim.kind != Primitive::Kind::kMesh || !prim.motion.empty()) continue;
    const TriangleMesh& mesh = scene.meshes[prim.mesh];
    // Indices past 2^31 / 3 would overflow the kernel's 32-bit gather offsets.
    if (!mesh.positionSteps.empty() || mesh.positions.size() >= (1u << 29) ||
        mesh.indices.size() >= (1u << 30))
      continue;
    SurfaceBatchPrimitive& p = primitives_[i];
    batched_[i] = 1;
    p.material = mesh.material;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) p.m[r][c] = prim.toWorld.m.m[r][c];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) p.inv[r][c] = prim.toWorld.inv.m[r][c];
    p.indices = mesh.indices.data();
    p.positions = &mesh.positions.data()->x;
    p.hasNormals = !mesh.normals.empty();
    p.normals = p.hasNormals ? &mesh.normals.data()->x : nullptr;
    p.hasUvs = !mesh.uvs.empty();
    p.uvs = p.hasUvs ? &mesh.uvs.data()->x : nullptr;
    useful_ = true;
  }
}

void SurfaceBatch::compute(std::span<const Ray> rays, std::span<const Hit> hits,
                           std::span<const uint8_t> found, std::span<SurfacePoint> out,
                           Scratch& scratch) const {
  // Counting sort of the batched hits by primitive; the others go to Scene::surface. The first
  // pass notes each hit's group (kNoPrimitive: none) for the second.
  if (scratch.count.size() < primitives_.size())
    scratch.count.assign(primitives_.size(), 0), scratch.begin.resize(primitives_.size());
  scratch.seen.clear();
  scratch.order.resize(hits.size());
  scratch.group.resize(hits.size());
  size_t batched = 0;
  for (size_t j = 0; j < hits.size(); ++j) {
    uint32_t prim = found[j] ? hits[j].primitive : kNoPrimitive;
    if (prim != kNoPrimitive && !batched_[prim]) {
      out[j] = scene_.surface(rays[j], hits[j]);
      prim = kNoPrimitive;
    }
    scratch.group[j] = prim;
    if (prim == kNoPrimitive) continue;
    if (scratch.count[prim]++ == 0) scratch.seen.push_back(prim);
    ++batched;
  }
  if (batched == 0) return;
  uint32_t start = 0;
  for (uint32_t prim : scratch.seen) scratch.begin[prim] = start, start += scratch.count[prim];
  for (size_t j = 0; j < hits.size(); ++j)
    if (scratch.group[j] != kNoPrimitive)
      scratch.order[scratch.begin[scratch.group[j]]++] = int32_t(j);
  start = 0;
  for (uint32_t prim : scratch.seen) {
    const uint32_t n = scratch.count[prim];
    HWY_DYNAMIC_DISPATCH(SurfaceGroup)
    (primitives_[prim], scratch.order.data() + start, n, hits.data(), rays.data(), out.data());
    start += n;
    scratch.count[prim] = 0;  // zero again for the next call
  }
}

}  // namespace tray
#endif  // HWY_ONCE

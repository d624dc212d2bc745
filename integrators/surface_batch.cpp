// Highway's dynamic dispatch, as integrators/camera_batch.cpp: compiled once per x86 target. The
// arithmetic is not here: it is meshSurfaceOf (core/surface_lanes.h), the one text that
// Scene::surface runs with float, compiled here for each target's vectors (docs/lanes.md). This
// file is the plumbing: hits grouped by primitive, their corners gathered, the results
// scattered to the hits' SurfacePoints.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/surface_batch.cpp"
#include "integrators/surface_batch.h"

#include <cstddef>
#include <limits>

#include "core/simd_lanes.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: the SIMD lane, then the one text for its vectors.
#include "core/lane_simd-inl.h"
#define TRAY_LANES_SIMD
#include "core/surface_lanes.h"
#undef TRAY_LANES_SIMD

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
// SurfaceBatch::useful() is false without a SIMD target: never called.
void SurfaceGroup(const SurfaceBatchPrimitive&, const int32_t*, size_t, const Hit*, const Ray*,
                  SurfacePoint*) {}
#else
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;
using V3 = Vec3Vec;

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

/// The first `count` lanes of a group's vector (count <= lanes): meshSurfaceOf for each, then
/// written to out at the hit's own index, with Scene::surface's frontFace, time and primitive.
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
  // Corner k's normal and uv, gathered where meshSurfaceOf reads them.
  const VI vertex[3] = {i0, i1, i2};
  const auto normal = [&](int k) { return Gather3(p.normals, vertex[k]); };
  const auto uv = [&](int k) -> Vec2Vec {
    const VI at = vertex[k] * hn::Set(di, 2);
    return {hn::GatherIndex(df, p.uvs, at), hn::GatherIndex(df, p.uvs + 1, at)};
  };
  MeshSurfaceOf<FloatVec> s;
  meshSurfaceOf(p.toWorld->m.m, p.toWorld->inv.m, FloatVec(b1), FloatVec(b2),
                Gather3(p.positions, i0), Gather3(p.positions, i1), Gather3(p.positions, i2),
                p.hasNormals, normal, p.hasUvs, uv, s);
  // To the hits' own SurfacePoints, lane by lane.
  HWY_ALIGN float lanes[14][kMaxSimdLanes];
  const FloatVec fields[14] = {s.p.x, s.p.y, s.p.z,  s.ng.x, s.ng.y,    s.ng.z,    s.n.x,
                               s.n.y, s.n.z, s.uv.x, s.uv.y, s.front.x, s.front.y, s.front.z};
  for (int f = 0; f < 14; ++f) hn::Store(fields[f].v, df, lanes[f]);
  for (size_t l = 0; l < count; ++l) {
    const Hit& hit = hits[order[l]];
    const Ray& ray = rays[order[l]];
    SurfacePoint& o = out[order[l]];
    o.p = {lanes[0][l], lanes[1][l], lanes[2][l]};
    const Vec3 sideNormal{lanes[3][l], lanes[4][l], lanes[5][l]};
    o.ng = sideNormal;
    o.n = {lanes[6][l], lanes[7][l], lanes[8][l]};
    o.uv = {lanes[9][l], lanes[10][l]};
    o.material = hit.material >= 0 ? hit.material : p.material;
    o.primitive = hit.primitive;
    o.front = {lanes[11][l], lanes[12][l], lanes[13][l]};
    o.frontFace = dot(ray.d, sideNormal) < 0;
    o.time = ray.time;
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
    // Instance arrays go to Scene::surface, which places each hit by its own instance (the
    // kernel takes one transform per group of hits).
    if (prim.kind != Primitive::Kind::kMesh || !prim.motion.empty() || prim.instances) continue;
    const TriangleMesh& mesh = scene.meshes[prim.mesh];
    // Indices past 2^31 / 3 would overflow the kernel's 32-bit gather offsets.
    if (!mesh.positionSteps.empty() || mesh.positions.size() >= (1u << 29) ||
        mesh.indices.size() >= (1u << 30))
      continue;
    SurfaceBatchPrimitive& p = primitives_[i];
    batched_[i] = 1;
    p.material = mesh.material;
    p.toWorld = &prim.toWorld;
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

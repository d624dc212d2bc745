#include "accel/embree_batch.h"

#include <algorithm>
#include <vector>

#include "accel/embree_alpha_filter.h"
#include "accel/embree_pack.h"
#include "accel/embree_rays.h"

namespace tray {
namespace {

constexpr int kLanes = 8;

/// Lane l of a packet from ray i (id i: the alpha filter's index into the batch's rays).
void toLane(const Ray& r, uint32_t i, RTCRay8& p, int l) {
  p.org_x[l] = r.o.x, p.org_y[l] = r.o.y, p.org_z[l] = r.o.z, p.tnear[l] = r.tmin;
  p.dir_x[l] = r.d.x, p.dir_y[l] = r.d.y, p.dir_z[l] = r.d.z, p.time[l] = r.time;
  p.tfar[l] = r.tmax, p.mask[l] = 0xffffffffu, p.id[l] = i, p.flags[l] = 0;
}

/// The lanes of rays Embree would refuse (embreeAccepts) made empty intervals, as toEmbree and
/// toEmbreeShadow do for one ray (`blocked`: a shadow query's, already occluded).
void emptyRefusedLanes(const Ray* rays, int lanes, RTCRay8& p, bool blocked) {
  for (int l = 0; l < lanes; ++l) {
    if (embreeAccepts(rays[l])) [[likely]]
      continue;
    RTCRay one;
    emptyRay(one, blocked);
    p.org_x[l] = one.org_x, p.org_y[l] = one.org_y, p.org_z[l] = one.org_z;
    p.dir_x[l] = one.dir_x, p.dir_y[l] = one.dir_y, p.dir_z[l] = one.dir_z;
    p.tnear[l] = one.tnear, p.tfar[l] = one.tfar;
  }
}

/// The valid mask of the packet starting at ray b: lanes past the batch's end are off.
void laneMask(size_t b, size_t n, int valid[kLanes]) {
  for (int l = 0; l < kLanes; ++l) valid[l] = b + size_t(l) < n ? -1 : 0;
}

/// A batch's mesh hit from lane l of a traced packet, field by field into its slot (building a
/// Hit and copying it in stalls on store forwarding, core/ray.h). Packets are only used on
/// scenes without user geometry (EmbreeAccelerator::streamable) but instance arrays, so every
/// hit is a mesh's: hitFromEmbree's look-up of the primitive's kind is not needed. An instance
/// array's hit carries its instance as geomID (accel/embree_instance_array.h), any other
/// instance's inner geometry id is 0.
void meshHitFromLane(const RTCRayHit8& p, int l, Hit& hit) {
  const uint32_t inst = p.hit.instID[0][l];
  hit.t = p.ray.tfar[l];
  hit.primitive = inst == RTC_INVALID_GEOMETRY_ID ? p.hit.geomID[l] : inst;
  hit.instance = inst == RTC_INVALID_GEOMETRY_ID ? 0 : p.hit.geomID[l];
  hit.triangle = p.hit.primID[l];
  hit.b1 = p.hit.u[l], hit.b2 = p.hit.v[l];
  hit.normal = Vec3(), hit.uv = Vec2(), hit.material = -1;
}

void intersectPackets(RTCScene top, RTCIntersectContext* ctx, std::span<const Ray> rays,
                      std::span<Hit> hits, std::span<uint8_t> found) {
  const size_t n = rays.size();
  // One packet for the whole batch, not zero-filled per group: Embree reads every lane, active
  // or not ("only active rays are processed", rtcIntersect8(3)), so an inactive lane need only
  // hold harmless numbers: the previous group's rays, or zeros in a batch's only, partial one.
  alignas(32) RTCRayHit8 p;
  if (n < size_t(kLanes)) p = {};
  for (size_t b = 0; b < n; b += kLanes) {
    alignas(32) int valid[kLanes];
    laneMask(b, n, valid);
    const int lanes = int(std::min(n - b, size_t(kLanes)));
    // The hit ids reset in each branch: over a constant 8 lanes the loop is two vector stores
    // (one loop over `lanes` after both: +0.5% of the Cornell box's instructions, callgrind).
    bool accepted;
    if (lanes == kLanes) {
      accepted = packRays8(&rays[b], uint32_t(b), p.ray);
      for (int l = 0; l < kLanes; ++l)
        p.hit.geomID[l] = p.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
    } else {
      accepted = false;  // checked lane by lane below
      for (int l = 0; l < lanes; ++l) {
        toLane(rays[b + l], uint32_t(b + l), p.ray, l);
        p.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
        p.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
      }
    }
    if (!accepted) [[unlikely]]
      emptyRefusedLanes(&rays[b], lanes, p.ray, false);
    rtcIntersect8(valid, top, ctx, &p);
    for (int l = 0; l < lanes; ++l) {
      const bool hit = p.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID;
      found[b + l] = hit;
      if (hit) meshHitFromLane(p, l, hits[b + l]);
    }
  }
}

void occludedPackets(RTCScene top, RTCIntersectContext* ctx, std::span<const Ray> rays,
                     std::span<uint8_t> blocked) {
  const size_t n = rays.size();
  alignas(32) RTCRay8 p;  // as in intersectPackets: inactive lanes keep earlier rays
  if (n < size_t(kLanes)) p = {};
  for (size_t b = 0; b < n; b += kLanes) {
    alignas(32) int valid[kLanes];
    laneMask(b, n, valid);
    const int lanes = int(std::min(n - b, size_t(kLanes)));
    bool accepted = false;  // a partial packet: checked lane by lane below
    if (lanes == kLanes)
      accepted = packRays8(&rays[b], uint32_t(b), p);
    else
      for (int l = 0; l < lanes; ++l) toLane(rays[b + l], uint32_t(b + l), p, l);
    if (!accepted) [[unlikely]]
      emptyRefusedLanes(&rays[b], lanes, p, true);
    rtcOccluded8(valid, top, ctx, &p);
    for (int l = 0; l < lanes; ++l) blocked[b + l] = p.tfar[l] < 0;
  }
}

}  // namespace

void embreeIntersectBatch(RTCScene top, const Scene& scene, EmbreeBatch mode,
                          std::span<const Ray> rays, std::span<Hit> hits, std::span<uint8_t> found,
                          bool coherent) {
  AlphaRayContext ctx(scene, rays.data());
  // Coherent 8-ray packets: Embree 3 traverses them with frustum culling per node (camera
  // rays 1.25-1.98x; incoherent rays lose by it, docs/wavefront.md). Streams stay incoherent:
  // with the coherent flag, Embree 3.13.5's rtcIntersect1M once failed to return.
  if (mode == EmbreeBatch::kPacket8) {
    ctx.base.flags =
        coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    return intersectPackets(top, &ctx.base, rays, hits, found);
  }
  ctx.base.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  static thread_local std::vector<RTCRayHit> queue;
  queue.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    queue[i] = toEmbree(rays[i]);
    queue[i].ray.id = uint32_t(i);  // the alpha filter's index into rays
  }
  rtcIntersect1M(top, &ctx.base, queue.data(), unsigned(queue.size()), sizeof(RTCRayHit));
  for (size_t i = 0; i < rays.size(); ++i) {
    found[i] = queue[i].hit.geomID != RTC_INVALID_GEOMETRY_ID;
    if (found[i]) hits[i] = hitFromEmbree(queue[i].hit, queue[i].ray.tfar, scene);
  }
}

void embreeOccludedBatch(RTCScene top, const Scene& scene, EmbreeBatch mode,
                         std::span<const Ray> rays, std::span<uint8_t> blocked) {
  AlphaRayContext ctx(scene, rays.data());
  if (mode == EmbreeBatch::kPacket8) return occludedPackets(top, &ctx.base, rays, blocked);
  ctx.base.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  static thread_local std::vector<RTCRay> queue;
  queue.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    toEmbreeShadow(rays[i], queue[i]);
    queue[i].id = uint32_t(i);
  }
  rtcOccluded1M(top, &ctx.base, queue.data(), unsigned(queue.size()), sizeof(RTCRay));
  for (size_t i = 0; i < rays.size(); ++i) blocked[i] = queue[i].tfar < 0;
}

}  // namespace tray

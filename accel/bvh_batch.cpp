#include "accel/bvh_batch.h"

#include <algorithm>
#include <vector>

#include "accel/bvh4_packet.h"
#include "accel/bvh_object_ray.h"
#include "textures/alpha.h"

namespace tray {
namespace {

/// The alpha test of one mesh primitive for ray r of a group, on its world-space ray (the hash
/// of stochastic transparency reads it), as the single-ray query's filter.
struct PacketAlpha {
  const Scene& scene;
  const Ray* worldRays;
  uint32_t primitive;
  static bool accept(const void* self, int r, uint32_t triangle, float b1, float b2) {
    auto* q = static_cast<const PacketAlpha*>(self);
    return alphaAccepts(q->scene, q->worldRays[r], q->primitive, triangle, b1, b2);
  }
  PacketTriangleFilter filter() const { return {&PacketAlpha::accept, this}; }
};

/// One group of up to kMaxPacketRays rays of a batch, traced together.
class Group {
 public:
  Group(const TwoLevelParts& parts, PacketRays& local, const Ray* rays, int n)
      : parts_(parts),
        local_(local),
        rays_(rays),
        all_(n == kMaxPacketRays ? ~RayMask(0) : (RayMask(1) << n) - 1) {
    for (int r = 0; r < n; ++r) tmin_[r] = rays[r].tmin, tmax_[r] = rays[r].tmax;
  }

  /// Closest hits into hits[0..n); bit r of the result: ray r hit something.
  RayMask intersect(Hit* hits) {
    RayMask found = 0;
    for (uint32_t i : *parts_.unbounded)
      for (RayMask m = all_; m; m &= m - 1)
        if (parts_.intersectPrimitive(i, rays_[nextRay(m)], tmax_[nextRay(m)], hits[nextRay(m)]))
          found |= m & -m;
    forEachPrimitive<true>(all_, all_,
                           [&](uint32_t i, RayMask m) { found |= intersectPrimitive(i, m, hits); });
    return found;
  }

  /// Bit r of the result: ray r is blocked.
  RayMask occluded() {
    RayMask alive = all_;
    for (RayMask m = alive; m; m &= m - 1)
      if (parts_.occludedByCached(rays_[nextRay(m)])) alive &= ~(m & -m);
    for (uint32_t i : *parts_.unbounded)
      for (RayMask m = alive; m; m &= m - 1)
        if (parts_.occludedPrimitive(i, rays_[nextRay(m)])) alive &= ~(m & -m);
    forEachPrimitive<false>(alive, alive,
                            [&](uint32_t i, RayMask m) { occludedPrimitive(i, m & alive, alive); });
    return all_ & ~alive;
  }

 private:
  /// visit(i, rays) for each placed primitive with the rays that enter its box.
  template <bool kOrdered, class Visit>
  void forEachPrimitive(RayMask active, const RayMask& alive, Visit&& visit) {
    if (!active) return;
    if (parts_.single != kNoPrimitive) return visit(parts_.single, active);
    for (RayMask m = active; m; m &= m - 1) {
      const Ray& ray = rays_[nextRay(m)];
      box_[nextRay(m)] = PacketBoxRay(ray.o, ray.d);
    }
    const Bvh4& top = *parts_.top;
    traversePacketBvh4<kOrdered>(top, box_, tmin_, tmax_, active, alive,
                                 [&](uint32_t first, uint32_t count, RayMask m) {
                                   for (uint32_t k = first; k < first + count; ++k)
                                     visit(top.primitives[k], m);
                                 });
  }

  /// The mesh a packet can descend, or null (analytic shapes, deforming meshes).
  const MeshBvh* packetMesh(const Primitive& p) const {
    if (p.kind != Primitive::Kind::kMesh) return nullptr;
    const MeshBvh* mesh = (*parts_.meshes)[p.mesh].get();
    return mesh->deforming() ? nullptr : mesh;
  }

  /// The rays of m in p's object space, into local_; the result leaves out those that cannot
  /// meet p (flat at their time).
  RayMask enter(const Primitive& p, uint32_t instance, RayMask m) {
    RayMask entered = 0;
    for (; m; m &= m - 1) {
      const int r = nextRay(m);
      Ray ray;
      if (!objectRay(p, instance, rays_[r], tmax_[r], ray)) continue;
      local_.set(r, ray);
      entered |= m & -m;
    }
    return entered;
  }

  /// The rays of m that enter each instance's box of a group (accel/bvh_instance_boxes.h),
  /// tested on the world-space rays of the top tree; a primitive's item: all of m.
  void splitByInstance(const TwoLevelParts::Placed& pl, RayMask m, RayMask* rays) const {
    for (uint32_t k = 0; k < kGroup; ++k) rays[k] = 0;
    if (!pl.boxes) return void(rays[0] = m);
    prefetchGroupMatrices(*parts_.scene->primitives[pl.primitive].instances, pl.instance, pl.count);
    for (; m; m &= m - 1) {
      const int r = nextRay(m);
      const unsigned in = hitGroupBoxes(pl.boxes, TwoLevelParts::kGroupBoxNodes,
                                        bvh4Ray(box_[r].o, box_[r].invD), tmin_[r], tmax_[r]);
      for (uint32_t k = 0; k < kGroup; ++k) rays[k] |= (m & -m) & -RayMask((in >> k) & 1);
    }
  }

  RayMask intersectPrimitive(uint32_t item, RayMask m, Hit* hits) {
    const TwoLevelParts::Placed pl = parts_.placed(item);
    const auto [i, first, count, boxes] = pl;
    const Primitive& p = parts_.scene->primitives[i];
    RayMask found = 0;
    if (const MeshBvh* mesh = packetMesh(p)) {
      const PacketAlpha alpha{*parts_.scene, rays_, i};
      const PacketTriangleFilter filter = alpha.filter();
      RayMask byInstance[kGroup];
      splitByInstance(pl, m, byInstance);
      for (uint32_t instance = first; instance < first + count; ++instance) {
        const RayMask entered = enter(p, instance, byInstance[instance - first]);
        if (!entered) continue;  // the packet traversal needs a ray
        const RayMask f = mesh->intersectPacket(local_, entered, tmax_, hits,
                                                (*parts_.alphaTested)[p.mesh] ? &filter : nullptr);
        for (RayMask r = f; r; r &= r - 1)
          hits[nextRay(r)].primitive = i, hits[nextRay(r)].instance = instance;
        found |= f;
      }
      return found;
    }
    for (; m; m &= m - 1) {
      const int r = nextRay(m);
      if (parts_.intersectPrimitive(item, rays_[r], tmax_[r], hits[r])) found |= m & -m;
    }
    return found;
  }

  void occludedPrimitive(uint32_t item, RayMask m, RayMask& alive) {
    const TwoLevelParts::Placed pl = parts_.placed(item);
    const auto [i, first, count, boxes] = pl;
    const Primitive& p = parts_.scene->primitives[i];
    if (const MeshBvh* mesh = packetMesh(p)) {
      const PacketAlpha alpha{*parts_.scene, rays_, i};
      const PacketTriangleFilter filter = alpha.filter();
      const bool alphaTested = (*parts_.alphaTested)[p.mesh];
      const RayMask before = alive;
      uint32_t block = 0, member = 0;
      RayMask byInstance[kGroup];
      splitByInstance(pl, m, byInstance);
      for (uint32_t instance = first; instance < first + count && (m & alive); ++instance) {
        const RayMask entered = enter(p, instance, byInstance[instance - first] & alive);
        if (!entered) continue;
        const RayMask wasAlive = alive;
        mesh->occludedPacket(local_, entered, alive, tmax_, block, alphaTested ? &filter : nullptr);
        if (alive != wasAlive) member = instance - first;  // block is this instance's
      }
      // The blocker of the group's highest-numbered blocked ray is cached: the next group's
      // first rays are its neighbours. As in the single-ray query, an alpha-tested mesh's
      // block is not (block 0 there: occludedBy refuses alpha-tested meshes).
      const RayMask newlyBlocked = before & ~alive;
      if (newlyBlocked && highestBit(newlyBlocked) >= lastBlocked_) {
        lastBlocked_ = highestBit(newlyBlocked);
        parts_.cacheOccluder(item, member, alphaTested ? 0 : block);
      }
      return;
    }
    for (; m; m &= m - 1)
      if (parts_.occludedPrimitive(item, rays_[nextRay(m)])) {  // caches its blocker
        alive &= ~(m & -m);
        lastBlocked_ = std::max(lastBlocked_, nextRay(m));
      }
  }

  static int highestBit(RayMask m) { return 63 - __builtin_clzll(m); }
  static constexpr uint32_t kGroup = TwoLevelParts::kArrayGroup;

  const TwoLevelParts& parts_;
  PacketRays& local_;  ///< object-space rays of the mesh being entered
  const Ray* rays_;
  const RayMask all_;
  PacketBoxRay box_[kMaxPacketRays];  ///< world-space rays for the top tree
  float tmin_[kMaxPacketRays], tmax_[kMaxPacketRays];
  int lastBlocked_ = -1;  ///< the highest-numbered ray whose blocker is in the cache
};

/// The rays of a batch in the order groups take them: stably sorted by direction octant (a
/// counting sort) when `byOctant`, so that a group's rays agree on which side of every box is
/// near and part later; as stream tracers order their streams (Tsakok 2009; Fuetterling et al.
/// 2015). index[k]: the batch position of rays[k] (null: batch order).
struct GroupOrder {
  std::span<const Ray> rays;
  const uint32_t* index = nullptr;
};

GroupOrder groupOrder(std::span<const Ray> rays, bool byOctant) {
  if (!byOctant) return {rays};
  static thread_local std::vector<uint32_t> index;
  static thread_local std::vector<Ray> sorted;
  auto octant = [](const Ray& r) {
    return int(r.d.x < 0) | int(r.d.y < 0) << 1 | int(r.d.z < 0) << 2;
  };
  size_t start[9] = {};
  for (const Ray& r : rays) ++start[octant(r) + 1];
  for (int k = 1; k < 9; ++k) start[k] += start[k - 1];
  index.resize(rays.size());
  sorted.resize(rays.size());
  for (uint32_t i = 0; i < rays.size(); ++i) {
    const size_t k = start[octant(rays[i])]++;
    index[k] = i;
    sorted[k] = rays[i];
  }
  return {sorted, index.data()};
}

}  // namespace

void twoLevelIntersectBatch(const TwoLevelParts& parts, int group, bool byOctant,
                            std::span<const Ray> rays, std::span<Hit> hits,
                            std::span<uint8_t> found) {
  group = std::clamp(group, 1, kMaxPacketRays);
  const GroupOrder order = groupOrder(rays, byOctant);
  static thread_local std::vector<Hit> sortedHits;
  if (order.index) sortedHits.resize(rays.size());
  Hit* groupHits = order.index ? sortedHits.data() : hits.data();
  PacketRays local;
  for (size_t b = 0; b < rays.size(); b += size_t(group)) {
    const int n = int(std::min(rays.size() - b, size_t(group)));
    const RayMask f = Group(parts, local, &order.rays[b], n).intersect(&groupHits[b]);
    for (int r = 0; r < n; ++r) {
      const size_t i = order.index ? order.index[b + r] : b + r;
      found[i] = (f >> r) & 1;
      if (order.index && found[i]) hits[i] = groupHits[b + r];
    }
  }
}

void twoLevelOccludedBatch(const TwoLevelParts& parts, int group, bool byOctant,
                           std::span<const Ray> rays, std::span<uint8_t> blocked) {
  group = std::clamp(group, 1, kMaxPacketRays);
  const GroupOrder order = groupOrder(rays, byOctant);
  PacketRays local;
  for (size_t b = 0; b < rays.size(); b += size_t(group)) {
    const int n = int(std::min(rays.size() - b, size_t(group)));
    const RayMask f = Group(parts, local, &order.rays[b], n).occluded();
    for (int r = 0; r < n; ++r) blocked[order.index ? order.index[b + r] : b + r] = (f >> r) & 1;
  }
}

}  // namespace tray

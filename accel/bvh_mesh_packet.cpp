// MeshBvh's packet queries: the rays of a packet descend the mesh tree together
// (accel/bvh4_packet.h), and at a leaf each block of four triangles is loaded once and tested
// against every ray that entered the leaf, by the single-ray query's four-lane watertight test
// with that ray's own tmin and tmax, lanes in the same order.
#include "accel/bvh_mesh.h"

namespace tray {

/// The blocks of every leaf the rays enter, with the rays that entered it; onBlock(block, rays)
/// tests them.
template <bool kOrdered, class OnBlock>
static void forEachLeafBlock(const Bvh4& bvh, bool hierarchy, uint32_t blocks,
                             const PacketRays& rays, RayMask active, const RayMask& alive,
                             const float* tmax, OnBlock&& onBlock) {
  auto leaf = [&](uint32_t first, uint32_t count, RayMask m) {
    for (uint32_t k = first; k < first + count && (m &= alive); ++k) onBlock(k, m);
  };
  if (!hierarchy) return leaf(0, blocks, active);
  traversePacketBvh4<kOrdered>(bvh, rays.box, rays.tmin, tmax, active, alive, leaf);
}

template <class Accept>
[[gnu::always_inline]] inline RayMask MeshBvh::closestHitPacket(const PacketRays& rays,
                                                                RayMask active, float* tmax,
                                                                Hit* hits,
                                                                const Accept& accept) const {
  RayMask found = 0;
  const RayMask alive = active;  // closest hit: every ray runs to the end
  forEachLeafBlock<true>(
      bvh_, hierarchy_, uint32_t(blocks_.size()), rays, active, alive, tmax,
      [&](uint32_t k, RayMask m) {
        const Triangle4& block = blocks_[k];
        for (; m; m &= m - 1) {
          const int r = nextRay(m);
          alignas(16) float t[4], b1[4], b2[4];
          const int mask =
              intersectWatertight4(rays.triangle[r], block, rays.tmin[r], tmax[r], t, b1, b2);
          // As MeshBvh::closestHit, with ray r's own tmax and filter.
          const auto acceptFor = [&](uint32_t triangle, float u, float v) {
            return accept(r, triangle, u, v);
          };
          if (closestLane(block, mask, t, b1, b2, tmax[r], hits[r], acceptFor)) found |= m & -m;
        }
      });
  return found;
}

template <class OnBlock>
[[gnu::always_inline]] inline void MeshBvh::anyHitPacket(const PacketRays& rays, RayMask active,
                                                         RayMask& alive, const float* tmax,
                                                         uint32_t& blocker,
                                                         OnBlock&& blocks) const {
  int lastBlocked = -1;
  forEachLeafBlock<false>(bvh_, hierarchy_, uint32_t(blocks_.size()), rays, active, alive, tmax,
                          [&](uint32_t k, RayMask m) {
                            const Triangle4& block = blocks_[k];
                            for (; m; m &= m - 1) {
                              const int r = nextRay(m);
                              alignas(16) float t[4], b1[4], b2[4];
                              const int mask = intersectWatertight4(
                                  rays.triangle[r], block, rays.tmin[r], tmax[r], t, b1, b2);
                              if (!mask || !blocks(r, block, mask, b1, b2)) continue;
                              alive &= ~(m & -m);
                              if (r >= lastBlocked) blocker = k, lastBlocked = r;
                            }
                          });
}

[[gnu::flatten]] RayMask MeshBvh::intersectPacket(const PacketRays& rays, RayMask active,
                                                  float* tmax, Hit* hits,
                                                  const PacketTriangleFilter* filter) const {
  if (filter)
    return closestHitPacket(rays, active, tmax, hits,
                            [&](int r, uint32_t triangle, float b1, float b2) {
                              return filter->accept(filter->data, r, triangle, b1, b2);
                            });
  return closestHitPacket(rays, active, tmax, hits,
                          [](int, uint32_t, float, float) { return true; });
}

[[gnu::flatten]] void MeshBvh::occludedPacket(const PacketRays& rays, RayMask active,
                                              RayMask& alive, const float* tmax,
                                              uint32_t& block,
                                              const PacketTriangleFilter* filter) const {
  if (!filter)
    return anyHitPacket(rays, active, alive, tmax, block,
                        [](int, const Triangle4&, int, const float*, const float*) {
                          return true;
                        });
  anyHitPacket(rays, active, alive, tmax, block,
               [&](int r, const Triangle4& block, int mask, const float* b1, const float* b2) {
                 return anyLaneAccepted(block, mask, b1, b2,
                                        [&](uint32_t triangle, float u, float v) {
                                          return filter->accept(filter->data, r, triangle, u, v);
                                        });
               });
}

}  // namespace tray

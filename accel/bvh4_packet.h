#pragma once
// Traversal of a Bvh4 by a group of up to 64 rays together, each node carrying the set of rays
// that entered it (a bit mask): the ray-stream traversal of Tsakok ("Faster Incoherent Rays:
// Multi-BVH Ray Stream Tracing", HPG 2009) and Fuetterling et al. ("Efficient Ray Tracing
// Kernels for Modern CPU Architectures", JCGT 4(5), 2015), with small groups (8 rays) making it
// a packet traversal. A node is fetched once for all its rays; each ray tests the node's four
// children with exactly the single-ray slab test (accel/bvh4_traversal.h), so it enters a child
// only where its own query would, and rays that miss a child never see that subtree.
#include <cstdint>

#include "accel/bvh4_traversal.h"

namespace tray {

constexpr int kMaxPacketRays = 64;
using RayMask = uint64_t;

/// A ray of a group as the box tests read it: Bvh4Ray's values before broadcasting, a quarter
/// of its size, so that a group of 64 takes 1.5 KB of the first-level cache rather than 7.
struct PacketBoxRay {
  float o[3], invD[3];
  PacketBoxRay() = default;
  PacketBoxRay(const Vec3& origin, const Vec3& d) {
    for (int i = 0; i < 3; ++i) o[i] = origin[i], invD[i] = safeInverse(d[i]);
  }
};

inline int nextRay(RayMask m) {
  return __builtin_ctzll(m);
}

/// Calls leaf(first, count, rays) for each leaf that the rays in `rays` enter, with the subset
/// that entered it. Closest hit (kOrdered): children are visited in order of the nearest entry
/// among their rays, and a subtree popped from the stack keeps only the rays whose tmax[r] (which
/// `leaf` lowers) still reaches that entry; as in the single-ray traversal, no box behind a ray's
/// closest hit is entered by that ray. Any hit (!kOrdered): slot order; `leaf` clears the bits of
/// rays it has blocked in `alive`, and no ray outside `alive` is carried further.
/// The rays are box[r], tmin[r], tmax[r] for each bit r of `rays` (other slots are not read).
template <bool kOrdered, class LeafFn>
void traversePacketBvh4(const Bvh4& bvh, const PacketBoxRay* box, const float* tmin, const float* tmax,
                        RayMask rays, const RayMask& alive, LeafFn&& leaf) {
  if (bvh.nodes.empty()) return;
  const Bvh4Node* nodes = bvh.nodes.data();
  struct Item {
    uint32_t ref;
    float entry;  ///< the nearest entry among its rays
    RayMask rays;
  };
  Item stack[kBvh4StackSize];
  int top = 0;
  uint32_t current = 0;
  for (;;) {
    if (bvh4ref::leaf(current)) {
      leaf(bvh4ref::first(current), bvh4ref::count(current), rays);
    } else if (!(rays & (rays - 1))) {
      // One ray left: the single-ray traversal is cheaper for this subtree, which the ray sees
      // as its own query would (Benthin et al., "Combining Single and Packet-Ray Tracing for
      // Arbitrary Ray Distributions on the Intel MIC Architecture", TVCG 2012). Incoherent rays
      // part at the first levels, so this is where they spend most of their time.
      const int r = nextRay(rays);
      traverseBvh4<kOrdered>(
          bvh, bvh4Ray(box[r].o, box[r].invD), tmin[r], tmax[r],
          [&](uint32_t first, uint32_t count) {
            leaf(first, count, rays);
            return !(alive & rays);  // blocked: done
          },
          current);
    } else {
      const Bvh4Node& n = nodes[current];
      RayMask childRays[4] = {0, 0, 0, 0};
      simd::F4 nearest = simd::set1(kInfinity);
      for (RayMask m = rays; m; m &= m - 1) {
        const int r = nextRay(m);
        simd::F4 entry;
        const simd::M4 hit =
            hitBoxes4Mask(n, bvh4Ray(box[r].o, box[r].invD), simd::set1(tmin[r]),
                          simd::set1(tmax[r]), entry);
        if constexpr (kOrdered) nearest = simd::min(nearest, simd::select(hit, entry, nearest));
        const int bits = simd::bits(hit);
        const RayMask bit = m & -m;
        for (int c = 0; c < 4; ++c) childRays[c] |= bit & -RayMask((bits >> c) & 1);
      }
      alignas(16) float entry[4];
      simd::store(entry, nearest);
      Item hit[4];
      int k = 0;
      for (int c = 0; c < 4; ++c) {
        if (!childRays[c]) continue;
        Item it{n.child[c], entry[c], childRays[c]};
        int j = k++;
        if constexpr (kOrdered)  // insertion sort, farthest first: at most four items
          for (; j > 0 && hit[j - 1].entry < it.entry; --j) hit[j] = hit[j - 1];
        hit[j] = it;
      }
      if (k) {
        for (int j = 0; j + 1 < k; ++j) stack[top++] = hit[j];
        current = hit[k - 1].ref;
        rays = hit[k - 1].rays;
        continue;
      }
    }
    // Pop the next subtree that still has rays: alive ones whose closest hit is beyond it.
    for (;;) {
      if (top == 0) return;
      const Item& it = stack[--top];
      RayMask m = it.rays & alive;
      if constexpr (kOrdered)
        for (RayMask k = m; k; k &= k - 1)
          if (!(it.entry <= tmax[nextRay(k)])) m &= ~(k & -k);
      if (m) {
        current = it.ref;
        rays = m;
        break;
      }
    }
  }
}

}  // namespace tray

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

/// The rays of a group as the box tests read them; slot r holds ray r (only the slots of rays in
/// the traversal's mask are read).
constexpr int kMaxPacketRays = 64;
using RayMask = uint64_t;

inline int nextRay(RayMask m) {
  return __builtin_ctzll(m);
}

/// Calls leaf(first, count, rays) for each leaf that the rays in `rays` enter, with the subset
/// that entered it. Closest hit (kOrdered): children are visited in order of the nearest entry
/// among their rays, and a subtree popped from the stack keeps only the rays whose tmax[r] (which
/// `leaf` lowers) still reaches that entry; as in the single-ray traversal, no box behind a ray's
/// closest hit is entered by that ray. Any hit (!kOrdered): slot order; `leaf` clears the bits of
/// rays it has blocked in `alive`, and no ray outside `alive` is carried further.
template <bool kOrdered, class LeafFn>
void traversePacketBvh4(const Bvh4& bvh, const Bvh4Ray* box, const float* tmin, const float* tmax,
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
    } else {
      const Bvh4Node& n = nodes[current];
      RayMask childRays[4] = {0, 0, 0, 0};
      simd::F4 nearest = simd::set1(kInfinity);
      for (RayMask m = rays; m; m &= m - 1) {
        const int r = nextRay(m);
        simd::F4 entry;
        const simd::M4 hit =
            hitBoxes4Mask(n, box[r], simd::set1(tmin[r]), simd::set1(tmax[r]), entry);
        if constexpr (kOrdered) nearest = simd::min(nearest, simd::select(hit, entry, nearest));
        for (int c = simd::bits(hit); c; c &= c - 1) childRays[__builtin_ctz(unsigned(c))] |= m & -m;
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

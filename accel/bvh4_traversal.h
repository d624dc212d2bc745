#pragma once
// Front-to-back traversal of a Bvh4 with a small fixed stack. At an interior node the four child
// boxes are tested at once; the children hit are visited nearest first, the others pushed with
// their entry distance, so a subtree is skipped when a closer hit has been found by the time it
// is popped (as Embree's BVH4 traversal, kernels/bvh/bvh_traverser1.h).
#include <cmath>
#include <cstdint>
#include <limits>

#include "accel/bvh4.h"
#include "accel/simd4.h"
#include "core/math.h"

namespace tray {

/// A ray prepared once for every box test: origin and reciprocal direction in all lanes, and per
/// axis which of lo/hi is the near plane (the direction's sign), so no per-box swap is needed.
struct Bvh4Ray {
  simd::F4 o[3], invD[3];
  bool negative[3];
};

/// The reciprocal of a direction component. Like Embree's rcp_safe: a zero component becomes
/// tiny, so 0 * inf never makes a NaN.
inline float safeInverse(float d) {
  return 1.0f / (std::fabs(d) < 1e-18f ? std::copysign(1e-18f, d) : d);
}

/// A Bvh4Ray from its origin and reciprocal direction.
inline Bvh4Ray bvh4Ray(const float o[3], const float invD[3]) {
  Bvh4Ray r;
  for (int i = 0; i < 3; ++i) {
    r.o[i] = simd::set1(o[i]);
    r.invD[i] = simd::set1(invD[i]);
    r.negative[i] = invD[i] < 0;
  }
  return r;
}

inline Bvh4Ray prepareBvh4Ray(const Vec3& o, const Vec3& d) {
  const float origin[3] = {o.x, o.y, o.z};
  const float inv[3] = {safeInverse(d.x), safeInverse(d.y), safeInverse(d.z)};
  return bvh4Ray(origin, inv);
}

/// Slab test of a node's four children; lane c of the mask (bit c of hitBoxes4's result) is set
/// when the ray enters child c within [tmin, tmax], and entry receives the entry distances. The
/// far distance is enlarged by 2 gamma(3) (pbrt-v3, section 3.9.2) so rounding never culls a box
/// that a watertight triangle test inside it would hit.
/// The boxes are lo/hi [axis][child] (a Bvh4Node's, or any four boxes laid out as one).
inline simd::M4 hitBoxes4Mask(const float (&lo)[3][4], const float (&hi)[3][4], const Bvh4Ray& r,
                              simd::F4 tmin, simd::F4 tmax, simd::F4& entry) {
  using namespace simd;
  constexpr float kEps = std::numeric_limits<float>::epsilon() * 0.5f;
  constexpr float kRobust = 1.0f + 2.0f * (3 * kEps) / (1 - 3 * kEps);
  F4 tNear = tmin, tFar = set1(kInfinity);
  for (int a = 0; a < 3; ++a) {
    const float* nearPlane = r.negative[a] ? hi[a] : lo[a];
    const float* farPlane = r.negative[a] ? lo[a] : hi[a];
    tNear = max(tNear, (load(nearPlane) - r.o[a]) * r.invD[a]);
    tFar = min(tFar, (load(farPlane) - r.o[a]) * r.invD[a]);
  }
  tFar = min(tFar * set1(kRobust), tmax);
  entry = tNear;
  return tNear <= tFar;
}
inline simd::M4 hitBoxes4Mask(const Bvh4Node& n, const Bvh4Ray& r, simd::F4 tmin, simd::F4 tmax,
                              simd::F4& entry) {
  return hitBoxes4Mask(n.lo, n.hi, r, tmin, tmax, entry);
}
inline int hitBoxes4(const Bvh4Node& n, const Bvh4Ray& r, simd::F4 tmin, simd::F4 tmax,
                     simd::F4& entry) {
  return simd::bits(hitBoxes4Mask(n, r, tmin, tmax, entry));
}

// Every 4-wide level consumes at least one binary level and pushes at most three children; the
// builders keep binary trees under 256 levels (Goldsmith–Salmon checks its depth).
constexpr int kBvh4StackSize = 3 * 256;

/// Calls leaf(first, count) for each leaf whose box the ray enters before `tmax`, nearest box
/// first (kOrdered; else in slot order, cheaper for any-hit queries, where the first hit found
/// ends the search wherever it lies). `leaf` may lower tmax (closest hit) and returns true to
/// stop (any hit). `root`: the subtree to traverse (packets hand a lone ray over,
/// accel/bvh4_packet.h).
template <bool kOrdered = true, class LeafFn>
bool traverseBvh4(const Bvh4& bvh, const Bvh4Ray& r, float tmin, const float& tmax, LeafFn&& leaf,
                  uint32_t root = 0) {
  if (bvh.nodes.empty()) return false;
  const Bvh4Node* nodes = bvh.nodes.data();
  struct Item {
    uint32_t ref;
    float entry;
  };
  Item stack[kBvh4StackSize];
  int top = 0;
  const simd::F4 tminv = simd::set1(tmin);
  uint32_t current = root;
  for (;;) {
    if (bvh4ref::leaf(current)) {
      if (leaf(bvh4ref::first(current), bvh4ref::count(current))) return true;
    } else {
      const Bvh4Node& n = nodes[current];
      simd::F4 entry4;
      int mask = hitBoxes4(n, r, tminv, simd::set1(tmax), entry4);
      if (mask) {
        alignas(16) float entry[4];
        simd::store(entry, entry4);
        Item hit[4];
        int k = 0;
        if constexpr (!kOrdered) {
          for (; mask; mask &= mask - 1) {
            int c = __builtin_ctz(unsigned(mask));
            hit[k++] = {n.child[c], entry[c]};
          }
          for (int j = 0; j + 1 < k; ++j) stack[top++] = hit[j];
          current = hit[k - 1].ref;
          continue;
        }
        for (; mask; mask &= mask - 1) {
          int c = __builtin_ctz(unsigned(mask));
          // Insertion sort, farthest first: at most four items.
          Item it{n.child[c], entry[c]};
          int j = k++;
          for (; j > 0 && hit[j - 1].entry < it.entry; --j) hit[j] = hit[j - 1];
          hit[j] = it;
        }
        for (int j = 0; j + 1 < k; ++j) stack[top++] = hit[j];
        current = hit[k - 1].ref;
        continue;
      }
    }
    // Pop the next subtree that may still hold a hit closer than tmax.
    for (;;) {
      if (top == 0) return false;
      const Item& it = stack[--top];
      if (it.entry <= tmax) {
        current = it.ref;
        break;
      }
    }
  }
}

}  // namespace tray

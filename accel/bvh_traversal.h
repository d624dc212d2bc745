#pragma once
// Front-to-back traversal of a flattened Bvh with a small fixed stack. At an interior node both
// children's boxes are tested; the nearer is visited next and the farther pushed with its entry
// distance, so it is skipped when a closer hit has been found by the time it is popped.
#include <cmath>
#include <cstdint>
#include <limits>

#include "accel/bvh.h"

namespace tray {

struct BvhRay {
  Vec3 o, invD;
};

inline BvhRay prepareBvhRay(const Vec3& o, const Vec3& d) {
  BvhRay r;
  r.o = o;
  for (int i = 0; i < 3; ++i) {
    // Like Embree's rcp_safe: a zero component becomes tiny, so 0 * inf never makes a NaN.
    float di = std::fabs(d[i]) < 1e-18f ? std::copysign(1e-18f, d[i]) : d[i];
    r.invD[i] = 1.0f / di;
  }
  return r;
}

/// Slab test. The far distance is enlarged by 2 gamma(3) (pbrt-v3, section 3.9.2) so rounding
/// never culls a box that a watertight triangle test inside it would hit.
inline bool hitBox(const BvhNode& n, const BvhRay& r, float tmin, float tmax, float& entry) {
  constexpr float kEps = std::numeric_limits<float>::epsilon() * 0.5f;
  constexpr float kRobust = 1.0f + 2.0f * (3 * kEps) / (1 - 3 * kEps);
  float t0 = tmin, t1 = tmax;
  for (int a = 0; a < 3; ++a) {
    float tn = (n.lo[a] - r.o[a]) * r.invD[a];
    float tf = (n.hi[a] - r.o[a]) * r.invD[a];
    if (tn > tf) std::swap(tn, tf);
    tf *= kRobust;
    t0 = tn > t0 ? tn : t0;
    t1 = tf < t1 ? tf : t1;
  }
  entry = t0;
  return t0 <= t1;
}

constexpr int kBvhStackSize = 256;  // builders keep trees shallower (Goldsmith–Salmon checks)

/// Calls leaf(first, count) for each leaf whose box the ray enters before `tmax`, nearest box
/// first. `leaf` may lower tmax (closest hit) and returns true to stop (any hit).
template <class LeafFn>
bool traverseBvh(const Bvh& bvh, const BvhRay& r, float tmin, const float& tmax, LeafFn&& leaf) {
  if (bvh.nodes.empty()) return false;
  const BvhNode* nodes = bvh.nodes.data();
  float entry;
  if (!hitBox(nodes[0], r, tmin, tmax, entry)) return false;
  struct Item {
    uint32_t node;
    float entry;
  };
  Item stack[kBvhStackSize];
  int top = 0;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& n = nodes[current];
    if (n.leaf()) {
      if (leaf(n.offset, uint32_t(n.count))) return true;
    } else {
      float e0, e1;
      bool h0 = hitBox(nodes[n.offset], r, tmin, tmax, e0);
      bool h1 = hitBox(nodes[n.offset + 1], r, tmin, tmax, e1);
      if (h0 && h1) {
        uint32_t nearChild = n.offset, farChild = n.offset + 1;
        if (e1 < e0) std::swap(nearChild, farChild), std::swap(e0, e1);
        stack[top++] = {farChild, e1};
        current = nearChild;
        continue;
      }
      if (h0 || h1) {
        current = h0 ? n.offset : n.offset + 1;
        continue;
      }
    }
    // Pop the next subtree that may still hold a hit closer than tmax.
    for (;;) {
      if (top == 0) return false;
      Item it = stack[--top];
      if (it.entry <= tmax) {
        current = it.node;
        break;
      }
    }
  }
}

}  // namespace tray

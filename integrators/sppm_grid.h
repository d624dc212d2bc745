#pragma once
// The spatial hash grid of SPPM's visible points (Hachisuka & Jensen 2009, sec. 4; pbrt-v3
// 16.2.4 enters each point in every cell its sphere overlaps, so that a photon looks up one
// cell). Radii differ widely (a pixel's footprint grows with distance: a floor reaching the
// horizon), so one cell size cannot fit them all: each point goes to the level whose cells are
// at least its diameter (level L: cells of 2^L times the smallest diameter), where its sphere
// overlaps at most 2 x 2 x 2 cells, and a photon looks up one cell per level in use. Built in
// parallel and deterministically: the (cell hash, point) pairs are sorted, so each bucket lists
// its points in increasing index whatever the threads.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/math.h"

namespace tray {

class VisiblePointGrid {
 public:
  /// Points p[i] with radius r[i]; a point whose radius is not positive is left out.
  VisiblePointGrid(std::span<const Vec3> p, std::span<const float> r);
  /// Calls fn(i) once for every point i whose sphere contains q: level by level, in increasing
  /// i within a level (an order that depends on the points alone).
  template <class Fn>
  void forEachNear(const Vec3& q, Fn&& fn) const {
    if (entries_.empty() || !bounds_.contains(q)) return;
    for (const uint8_t level : levelsUsed_) {
      const uint32_t h = hashOf(level, q);
      uint32_t last = ~0u;
      for (uint32_t e = start_[h]; e < start_[h + 1]; ++e) {
        const uint32_t i = uint32_t(entries_[e]);
        // Another level's point (the hashes collided) is found in its own level's pass; a
        // point whose cells collided in one bucket is there more than once: once is enough.
        if (i == last || level_[i] != level) continue;
        last = i;
        const Vec3 d = q - points_[i];
        if (dot(d, d) < radii_[i] * radii_[i]) fn(i);
      }
    }
  }
  size_t entryCount() const { return entries_.size(); }

 private:
  struct Box {
    Vec3 lo{kInfinity}, hi{-kInfinity};
    bool contains(const Vec3& q) const {
      return q.x >= lo.x && q.y >= lo.y && q.z >= lo.z && q.x <= hi.x && q.y <= hi.y && q.z <= hi.z;
    }
  };
  /// The cell of coordinate x along axis a at a level (clamped: no overflow).
  int cellIndex(float x, int a, int level) const {
    const float t = (x - bounds_.lo[a]) / std::ldexp(baseCell_, level);
    return int(std::clamp(t, 0.0f, float(1 << 30)));
  }
  uint32_t hashOf(int level, const int c[3]) const {
    const uint64_t h = uint64_t(uint32_t(c[0])) * 73856093u ^ uint64_t(uint32_t(c[1])) * 19349663u ^
                       uint64_t(uint32_t(c[2])) * 83492791u ^ uint64_t(level) * 2654435761u;
    return uint32_t(h % buckets_);
  }
  uint32_t hashOf(int level, const Vec3& q) const {
    const int c[3] = {cellIndex(q.x, 0, level), cellIndex(q.y, 1, level), cellIndex(q.z, 2, level)};
    return hashOf(level, c);
  }
  std::span<const Vec3> points_;
  std::span<const float> radii_;
  Box bounds_;                       ///< of every sphere
  float baseCell_ = 1;               ///< level 0's cell: the smallest diameter
  std::vector<uint8_t> level_;       ///< per point
  std::vector<uint8_t> levelsUsed_;  ///< in increasing order
  uint32_t buckets_ = 1;
  /// Sorted (bucket << 32 | point); start_[b] .. start_[b + 1] are bucket b's.
  std::vector<uint64_t> entries_;
  std::vector<uint32_t> start_;
};

}  // namespace tray

#pragma once
// The spatial hash grid of SPPM's visible points (Hachisuka & Jensen 2009, sec. 4; the structure
// of pbrt-v3 16.2.4): each point is entered in every cell its sphere of radius r overlaps, so a
// photon looks up one cell. Built in parallel and deterministically: the (cell hash, point)
// pairs are sorted, so each cell lists its points in increasing index whatever the threads.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/bounds.h"
#include "core/math.h"

namespace tray {

class VisiblePointGrid {
 public:
  /// Points p[i] with radius r[i]; a point whose radius is not positive is left out.
  VisiblePointGrid(std::span<const Vec3> p, std::span<const float> r);
  /// Calls fn(i) once for every point i whose sphere contains q, in increasing i.
  template <class Fn>
  void forEachNear(const Vec3& q, Fn&& fn) const {
    if (entries_.empty()) return;
    int c[3];
    if (!cellOf(q, c)) return;
    const uint32_t h = hashOf(c);
    uint32_t last = ~0u;
    for (uint32_t e = start_[h]; e < start_[h + 1]; ++e) {
      const uint32_t i = uint32_t(entries_[e]);
      if (i == last) continue;  // the point's cells collided in the hash: once is enough
      last = i;
      const Vec3 d = q - points_[i];
      if (dot(d, d) < radii_[i] * radii_[i]) fn(i);
    }
  }
  size_t entryCount() const { return entries_.size(); }

 private:
  bool cellOf(const Vec3& q, int c[3]) const;
  /// The cell of coordinate x along axis a, from the bounds' corner (clamped: no overflow).
  int cellIndex(float x, int a) const {
    const float t = (x - bounds_.lo[a]) / cellSize_;
    return int(std::clamp(t, 0.0f, float(1 << 30)));
  }
  uint32_t hashOf(const int c[3]) const {
    const uint64_t h = uint64_t(uint32_t(c[0])) * 73856093u ^ uint64_t(uint32_t(c[1])) * 19349663u ^
                       uint64_t(uint32_t(c[2])) * 83492791u;
    return uint32_t(h % buckets_);
  }
  std::span<const Vec3> points_;
  std::span<const float> radii_;
  Bounds3 bounds_;
  float cellSize_ = 1;
  uint32_t buckets_ = 1;
  /// Sorted (bucket << 32 | point); start_[b] .. start_[b + 1] are bucket b's.
  std::vector<uint64_t> entries_;
  std::vector<uint32_t> start_;
};

}  // namespace tray

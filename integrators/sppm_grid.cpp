#include "integrators/sppm_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>

namespace tray {
namespace {

/// Bounds of the points' spheres and their largest radius: min and max are exact, so the
/// parallel reduction gives the same bounds for any split.
struct Extent {
  Bounds3 bounds;
  float maxRadius = 0;
};

Extent extentOf(std::span<const Vec3> p, std::span<const float> r) {
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, p.size(), 4096), Extent{},
      [&](const tbb::blocked_range<size_t>& range, Extent e) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
          if (!(r[i] > 0)) continue;
          e.bounds.extend(p[i] - Vec3(r[i]));
          e.bounds.extend(p[i] + Vec3(r[i]));
          e.maxRadius = std::max(e.maxRadius, r[i]);
        }
        return e;
      },
      [](Extent a, const Extent& b) {
        a.bounds.extend(b.bounds);
        a.maxRadius = std::max(a.maxRadius, b.maxRadius);
        return a;
      });
}

}  // namespace

bool VisiblePointGrid::cellOf(const Vec3& q, int c[3]) const {
  for (int a = 0; a < 3; ++a) {
    if (!(q[a] >= bounds_.lo[a] && q[a] <= bounds_.hi[a])) return false;  // outside all (or NaN)
    c[a] = cellIndex(q[a], a);
  }
  return true;
}

VisiblePointGrid::VisiblePointGrid(std::span<const Vec3> p, std::span<const float> r)
    : points_(p), radii_(r) {
  const Extent extent = extentOf(p, r);
  if (extent.bounds.empty() || !extent.bounds.finite() || !(extent.maxRadius > 0)) return;
  bounds_ = extent.bounds;
  // Cells twice the largest radius across (pbrt-v3 takes about the radius): a sphere then
  // overlaps at most 2 x 2 x 2 cells. At most ~2^30 cells, whatever the spread of the points.
  // Cells twice the largest radius across (pbrt-v3 takes about the radius): a sphere then
  // overlaps at most 2 x 2 x 2 cells. The cells are hashed, not stored: points spread over a
  // large extent (a floor reaching the horizon) cost nothing.
  cellSize_ = 2 * extent.maxRadius;
  buckets_ = uint32_t(std::max<size_t>(1, p.size()));

  // Each point's cells: count, offsets, then the (bucket, point) pairs, sorted.
  std::vector<uint32_t> count(p.size() + 1, 0);
  auto cellRange = [&](size_t i, int lo[3], int hi[3]) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = cellIndex(p[i][a] - r[i], a);
      hi[a] = cellIndex(p[i][a] + r[i], a);
    }
  };
  tbb::parallel_for(size_t(0), p.size(), [&](size_t i) {
    if (!(r[i] > 0)) return;
    int lo[3], hi[3];
    cellRange(i, lo, hi);
    count[i + 1] = uint32_t((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1));
  });
  for (size_t i = 0; i < p.size(); ++i) count[i + 1] += count[i];
  entries_.resize(count.back());
  tbb::parallel_for(size_t(0), p.size(), [&](size_t i) {
    if (!(r[i] > 0)) return;
    int lo[3], hi[3], c[3];
    cellRange(i, lo, hi);
    uint64_t* out = entries_.data() + count[i];
    for (c[2] = lo[2]; c[2] <= hi[2]; ++c[2])
      for (c[1] = lo[1]; c[1] <= hi[1]; ++c[1])
        for (c[0] = lo[0]; c[0] <= hi[0]; ++c[0]) *out++ = uint64_t(hashOf(c)) << 32 | i;
  });
  tbb::parallel_sort(entries_.begin(), entries_.end());  // unique keys: one order
  start_.assign(size_t(buckets_) + 1, 0);
  for (uint64_t e : entries_) ++start_[(e >> 32) + 1];
  for (size_t b = 0; b < buckets_; ++b) start_[b + 1] += start_[b];
}

}  // namespace tray

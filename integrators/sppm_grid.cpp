#include "integrators/sppm_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

namespace tray {
namespace {

/// Bounds of the points' spheres, their smallest radius and the levels in use (a bit each):
/// min, max and or are exact, so the parallel reduction gives the same for any split.
struct Extent {
  Vec3 lo{kInfinity}, hi{-kInfinity};
  float minRadius = kInfinity;
};

Extent extentOf(std::span<const Vec3> p, std::span<const float> r) {
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, p.size(), 4096), Extent{},
      [&](const tbb::blocked_range<size_t>& range, Extent e) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
          if (!(r[i] > 0) || !isFinite(p[i]) || !std::isfinite(r[i])) continue;
          e.lo = min(e.lo, p[i] - Vec3(r[i]));
          e.hi = max(e.hi, p[i] + Vec3(r[i]));
          e.minRadius = std::min(e.minRadius, r[i]);
        }
        return e;
      },
      [](Extent a, const Extent& b) {
        a.lo = min(a.lo, b.lo), a.hi = max(a.hi, b.hi);
        a.minRadius = std::min(a.minRadius, b.minRadius);
        return a;
      });
}

constexpr int kMaxLevel = 40;

}  // namespace

VisiblePointGrid::VisiblePointGrid(std::span<const Vec3> p, std::span<const float> r)
    : points_(p), radii_(r), level_(p.size(), 0) {
  const Extent extent = extentOf(p, r);
  if (!(extent.minRadius < kInfinity)) return;  // no point
  bounds_.lo = extent.lo, bounds_.hi = extent.hi;
  baseCell_ = 2 * extent.minRadius;
  buckets_ = uint32_t(std::max<size_t>(1, p.size()));
  auto kept = [&](size_t i) { return r[i] > 0 && isFinite(p[i]) && std::isfinite(r[i]); };
  // Each point's level: the first whose cells are at least its diameter.
  const uint64_t used = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, p.size(), 4096), uint64_t(0),
      [&](const tbb::blocked_range<size_t>& range, uint64_t mask) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
          if (!kept(i)) continue;
          int level = 0;
          while (level < kMaxLevel && std::ldexp(baseCell_, level) < 2 * r[i]) ++level;
          level_[i] = uint8_t(level);
          mask |= uint64_t(1) << level;
        }
        return mask;
      },
      [](uint64_t a, uint64_t b) { return a | b; });
  for (int level = 0; level <= kMaxLevel; ++level)
    if (used >> level & 1) levelsUsed_.push_back(uint8_t(level));

  // Each point's cells: count, offsets, then the (bucket, point) pairs, sorted.
  auto cellRange = [&](size_t i, int lo[3], int hi[3]) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = cellIndex(p[i][a] - r[i], a, level_[i]);
      hi[a] = cellIndex(p[i][a] + r[i], a, level_[i]);
    }
  };
  std::vector<uint32_t> count(p.size() + 1, 0);
  tbb::parallel_for(size_t(0), p.size(), [&](size_t i) {
    if (!kept(i)) return;
    int lo[3], hi[3];
    cellRange(i, lo, hi);
    count[i + 1] = uint32_t((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1));
  });
  for (size_t i = 0; i < p.size(); ++i) count[i + 1] += count[i];
  entries_.resize(count.back());
  tbb::parallel_for(size_t(0), p.size(), [&](size_t i) {
    if (!kept(i)) return;
    int lo[3], hi[3], c[3];
    cellRange(i, lo, hi);
    uint64_t* out = entries_.data() + count[i];
    for (c[2] = lo[2]; c[2] <= hi[2]; ++c[2])
      for (c[1] = lo[1]; c[1] <= hi[1]; ++c[1])
        for (c[0] = lo[0]; c[0] <= hi[0]; ++c[0]) *out++ = uint64_t(hashOf(level_[i], c)) << 32 | i;
  });
  tbb::parallel_sort(entries_.begin(), entries_.end());  // one order: equal keys are equal
  start_.assign(size_t(buckets_) + 1, 0);
  for (uint64_t e : entries_) ++start_[(e >> 32) + 1];
  for (size_t b = 0; b < buckets_; ++b) start_[b + 1] += start_[b];
}

}  // namespace tray

// Top-down binned SAH build: Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies" (IEEE RT 2007). Centroids are binned along all three axes in one pass; the best of
// the bins-1 planes per axis by SAH wins, or the node becomes a leaf when that is cheaper.
// Parallel in two ways (TBB): the binning pass of a large node is a parallel reduction, and the
// two children are built with parallel_invoke. Children are allocated in pairs from an atomic
// counter, so threads never contend on anything else.
//
// Speed (bench/accel_bench.cpp): primitive references are 32 bytes, two 4-float boxes corners
// moved by the partition, so every pass reads memory in order; boxes are merged four floats at
// a time (accel/simd4.h); bins hold boxes only, and the partition pass gathers the children's
// centroid bounds as it goes (as Embree's builders do), instead of a bin of centroids per bin.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstring>
#include <memory>

#include "accel/bvh.h"
#include "accel/simd4.h"

namespace tray {
namespace {

using simd::F4;

constexpr int kMaxBins = 32;
constexpr uint32_t kParallelBinning = 16 * 1024;  // below this, one thread bins faster
constexpr uint32_t kParallelChildren = 2 * 1024;

/// A box as two 4-float corners (the fourth lane is unused).
struct Box {
  F4 lo = simd::set1(kInfinity), hi = simd::set1(-kInfinity);
  void extend(F4 l, F4 h) { lo = simd::min(lo, l), hi = simd::max(hi, h); }
  void extend(const Box& b) { extend(b.lo, b.hi); }
  Bounds3 bounds() const {
    alignas(16) float l[4], h[4];
    simd::store(l, lo);
    simd::store(h, hi);
    return {{l[0], l[1], l[2]}, {h[0], h[1], h[2]}};
  }
  float area() const { return bounds().surfaceArea(); }
};

/// A primitive's box; the fourth lane of lo carries the primitive id's bits. Only min/max touch
/// that lane, never arithmetic. Centroids are taken doubled (lo + hi) throughout.
struct alignas(16) PrimRef {
  float lo[4], hi[4];
  F4 l() const { return simd::load(lo); }
  F4 h() const { return simd::load(hi); }
  uint32_t id() const {
    uint32_t i;
    std::memcpy(&i, &lo[3], 4);
    return i;
  }
  float centroid(int a) const { return lo[a] + hi[a]; }
  /// The id lane is cleared first (hi's fourth lane is 0), so no arithmetic sees its bits.
  F4 centroid4() const { return simd::xyz(l()) + h(); }
};

/// Plain data (no initialisers): a node initialises only the bins it uses.
struct Bin {
  F4 lo, hi;
  uint32_t count;
  Box box() const { return {lo, hi}; }
  void extend(F4 l, F4 h) { lo = simd::min(lo, l), hi = simd::max(hi, h); }
};

/// Bins of all three axes for one node. Only the first `used` bins of each axis are initialised
/// and touched: for the many small nodes near the leaves this fixed cost is most of the work.
struct Binning {
  Bin bins[3][kMaxBins];
  int used;
  explicit Binning(int n) : used(n) {
    for (auto& axis : bins)
      for (int i = 0; i < used; ++i) axis[i] = {simd::set1(kInfinity), simd::set1(-kInfinity), 0};
  }
  void merge(const Binning& o) {
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < used; ++i) {
        bins[a][i].extend(o.bins[a][i].lo, o.bins[a][i].hi);
        bins[a][i].count += o.bins[a][i].count;
      }
  }
};

/// Maps a doubled centroid to its bin along each axis.
struct BinMap {
  float lo[3], scale[3];
  int bins;
  int of(const PrimRef& r, int a) const {
    int i = int((r.centroid(a) - lo[a]) * scale[a]);
    return std::clamp(i, 0, bins - 1);
  }
};

class SahBuilder {
 public:
  SahBuilder(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options) : opt_(options) {
    opt_.bins = std::clamp(opt_.bins, 2, kMaxBins);
    opt_.maxLeafSize = std::clamp(opt_.maxLeafSize, 1, 16);  // the 4-wide leaf limit (bvh4.h)
    opt_.blockSize = std::clamp(opt_.blockSize, 1, opt_.maxLeafSize);
    opt_.sahDepth = std::clamp(opt_.sahDepth, 0, 200);
    refs_.reserve(bounds.size());
    for (uint32_t i = 0; i < bounds.size(); ++i) {
      const Bounds3& b = bounds[i];
      if (b.empty() || !b.finite()) continue;
      PrimRef r;
      for (int a = 0; a < 3; ++a) r.lo[a] = b.lo[a], r.hi[a] = b.hi[a];
      std::memcpy(&r.lo[3], &i, 4);
      r.hi[3] = 0.0f;
      refs_.push_back(r);
    }
  }

  Bvh build() {
    Bvh bvh;
    if (refs_.empty()) return bvh;
    // Uninitialised: every node up to nodeCount_ is written exactly once by the build.
    // Built in place in the result (a copy would hold the 2n nodes twice at the peak: 64 MiB
    // per 10^6 instances, bench/instancing_bench); nodes past nodeCount_ are cut off below.
    bvh.nodes.resize(2 * refs_.size());
    nodes_ = bvh.nodes.data();
    nodeCount_ = 1;
    struct Both {
      Box b, cb;
    };
    Both all = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, refs_.size(), 16384), Both{},
        [&](const tbb::blocked_range<size_t>& r, Both acc) {
          for (size_t k = r.begin(); k < r.end(); ++k) {
            acc.b.extend(refs_[k].l(), refs_[k].h());
            F4 c = refs_[k].centroid4();
            acc.cb.extend(c, c);
          }
          return acc;
        },
        [](Both x, const Both& y) {
          x.b.extend(y.b);
          x.cb.extend(y.cb);
          return x;
        });
    buildNode(0, 0, uint32_t(refs_.size()), all.b, all.cb, 0);
    bvh.nodes.resize(nodeCount_.load());
    bvh.primitives.resize(refs_.size());
    tbb::parallel_for(size_t(0), refs_.size(), size_t(16384), [&](size_t k0) {
      for (size_t k = k0; k < std::min(refs_.size(), k0 + 16384); ++k)
        bvh.primitives[k] = refs_[k].id();
    });
    return bvh;
  }

 private:
  /// Intersection tests for n primitives, tested blockSize at a time.
  float blocks(uint32_t n) const { return float((n + opt_.blockSize - 1) / opt_.blockSize); }

  void makeLeaf(uint32_t node, uint32_t begin, uint32_t end, const Box& b) {
    BvhNode& n = nodes_[node];
    n.setBounds(b.bounds());
    n.offset = begin;
    n.count = uint16_t(end - begin);
    n.axis = 0;
    n.pad = 0;
  }

  void binInto(Binning& acc, uint32_t begin, uint32_t end, const BinMap& map) const {
    for (uint32_t k = begin; k < end; ++k) {
      const PrimRef& ref = refs_[k];
      const F4 l = ref.l(), h = ref.h();
      for (int a = 0; a < 3; ++a) {
        Bin& bin = acc.bins[a][map.of(ref, a)];
        bin.extend(l, h);
        ++bin.count;
      }
    }
  }

  /// Bins [begin, end) into `out`; large ranges as a parallel reduction.
  void binRange(Binning& out, uint32_t begin, uint32_t end, const BinMap& map) const {
    if (end - begin < kParallelBinning) return binInto(out, begin, end, map);
    out = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(begin, end, 4096), Binning(map.bins),
        [&](const tbb::blocked_range<uint32_t>& r, Binning acc) {
          binInto(acc, r.begin(), r.end(), map);
          return acc;
        },
        [](Binning x, const Binning& y) {
          x.merge(y);
          return x;
        });
  }

  void buildNode(uint32_t node, uint32_t begin, uint32_t end, const Box& b, const Box& cb,
                 int depth) {
    const uint32_t n = end - begin;
    if (n == 1) return makeLeaf(node, begin, end, b);
    const Bounds3 cbb = cb.bounds();
    const Vec3 extent = cbb.diagonal();
    if (maxComponent(extent) <= 0.0f) {
      // All centroids coincide: no plane separates them. Split the range in half.
      if (n <= uint32_t(opt_.maxLeafSize)) return makeLeaf(node, begin, end, b);
      return splitAt(node, begin, begin + n / 2, end, b, 0, depth);
    }
    if (depth >= opt_.sahDepth) {
      if (n <= uint32_t(opt_.maxLeafSize)) return makeLeaf(node, begin, end, b);
      return medianSplit(node, begin, end, b, extent, depth);
    }
    // Small nodes get fewer bins (no fewer than 4): as good a split, for less fixed cost.
    const int nb = std::min(opt_.bins, std::max(4, int(n)));
    BinMap map;
    map.bins = nb;
    for (int a = 0; a < 3; ++a) {
      map.lo[a] = cbb.lo[a];
      map.scale[a] = extent[a] > 0 ? float(nb) * (1.0f - 1e-6f) / extent[a] : 0.0f;
    }
    Binning binning(map.bins);
    binRange(binning, begin, end, map);

    // Sweep each axis: right-to-left accumulated areas, then left-to-right to evaluate planes.
    float bestCost = kInfinity;
    int bestAxis = -1, bestPlane = 0;
    for (int a = 0; a < 3; ++a) {
      if (extent[a] <= 0) continue;
      const auto& bins = binning.bins[a];
      std::array<float, kMaxBins> rightArea;  // [1, nb) written before read
      std::array<uint32_t, kMaxBins> rightCount;
      Box acc;
      uint32_t count = 0;
      for (int i = nb - 1; i > 0; --i) {
        acc.extend(bins[i].box());
        count += bins[i].count;
        rightArea[i] = acc.area();
        rightCount[i] = count;
      }
      acc = Box();
      count = 0;
      for (int i = 0; i < nb - 1; ++i) {
        acc.extend(bins[i].box());
        count += bins[i].count;
        if (count == 0 || rightCount[i + 1] == 0) continue;
        float cost = acc.area() * blocks(count) + rightArea[i + 1] * blocks(rightCount[i + 1]);
        if (cost < bestCost) bestCost = cost, bestAxis = a, bestPlane = i;
      }
    }
    float area = b.area();
    float splitCost =
        opt_.traversalCost + opt_.intersectionCost * bestCost / std::max(area, 1e-30f);
    float leafCost = opt_.intersectionCost * blocks(n);
    if (n <= uint32_t(opt_.maxLeafSize) && leafCost <= splitCost)
      return makeLeaf(node, begin, end, b);
    // Every centroid fell into one bin on every axis: fall back to an object median.
    if (bestAxis < 0) return medianSplit(node, begin, end, b, extent, depth);
    Box lcb, rcb;
    uint32_t mid = partition(begin, end, map, bestAxis, bestPlane, lcb, rcb);
    Box lb, rb;
    for (int i = 0; i < nb; ++i) (i <= bestPlane ? lb : rb).extend(binning.bins[bestAxis][i].box());
    children(node, begin, mid, end, b, bestAxis, lb, lcb, rb, rcb, depth);
  }

  /// Splits at the median centroid along the axis of largest centroid extent.
  void medianSplit(uint32_t node, uint32_t begin, uint32_t end, const Box& b, const Vec3& extent,
                   int depth) {
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(
        refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
        [&](const PrimRef& x, const PrimRef& y) { return x.centroid(axis) < y.centroid(axis); });
    splitAt(node, begin, mid, end, b, axis, depth);
  }

  /// In-place two-sided partition (Hoare): refs left of the plane first. Gathers both sides'
  /// centroid bounds on the way, which the children's binning needs.
  uint32_t partition(uint32_t begin, uint32_t end, const BinMap& map, int axis, int plane, Box& lcb,
                     Box& rcb) {
    uint32_t i = begin, j = end;
    auto left = [&](const PrimRef& r) { return map.of(r, axis) <= plane; };
    for (;;) {
      while (i < j && left(refs_[i])) {
        F4 c = refs_[i++].centroid4();
        lcb.extend(c, c);
      }
      while (i < j && !left(refs_[j - 1])) {
        F4 c = refs_[--j].centroid4();
        rcb.extend(c, c);
      }
      if (i >= j) return i;
      std::swap(refs_[i], refs_[j - 1]);
    }
  }

  /// Splits [begin, end) at mid without bin information: recomputes the children's bounds.
  void splitAt(uint32_t node, uint32_t begin, uint32_t mid, uint32_t end, const Box& b, int axis,
               int depth) {
    Box lb, lcb, rb, rcb;
    for (uint32_t k = begin; k < end; ++k) {
      F4 c = refs_[k].centroid4();
      (k < mid ? lb : rb).extend(refs_[k].l(), refs_[k].h());
      (k < mid ? lcb : rcb).extend(c, c);
    }
    children(node, begin, mid, end, b, axis, lb, lcb, rb, rcb, depth);
  }

  void children(uint32_t node, uint32_t begin, uint32_t mid, uint32_t end, const Box& b, int axis,
                const Box& lb, const Box& lcb, const Box& rb, const Box& rcb, int depth) {
    uint32_t first = nodeCount_.fetch_add(2);
    BvhNode& n = nodes_[node];
    n.setBounds(b.bounds());
    n.offset = first;
    n.count = 0;
    n.axis = uint8_t(axis);
    n.pad = 0;
    auto leftChild = [&] { buildNode(first, begin, mid, lb, lcb, depth + 1); };
    auto rightChild = [&] { buildNode(first + 1, mid, end, rb, rcb, depth + 1); };
    if (end - begin >= kParallelChildren) {
      tbb::parallel_invoke(leftChild, rightChild);
    } else {
      leftChild();
      rightChild();
    }
  }

  BvhBuildOptions opt_;
  std::vector<PrimRef> refs_;
  BvhNode* nodes_ = nullptr;  ///< the result's nodes while building
  std::atomic<uint32_t> nodeCount_{0};
};

}  // namespace

Bvh buildBvhBinnedSah(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options) {
  return SahBuilder(bounds, options).build();
}

Bvh buildBvhBinnedSah(std::vector<Bounds3>&& bounds, const BvhBuildOptions& options) {
  SahBuilder builder(bounds, options);
  std::vector<Bounds3>().swap(bounds);  // the builder holds its own copy: freed before building
  return builder.build();
}

}  // namespace tray

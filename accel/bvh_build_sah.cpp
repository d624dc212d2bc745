// Top-down binned SAH build: Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies" (IEEE RT 2007). Centroids are binned along all three axes in one pass; the best of
// the bins-1 planes per axis by SAH wins, or the node becomes a leaf when that is cheaper.
// Parallel in two ways (TBB): the binning pass of a large node is a parallel reduction, and the
// two children are built with parallel_invoke. Children are allocated in pairs from an atomic
// counter, so threads never contend on anything else.
#include <tbb/blocked_range.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <atomic>

#include "accel/bvh.h"

namespace tray {
namespace {

constexpr int kMaxBins = 32;
constexpr uint32_t kParallelBinning = 32 * 1024;  // below this, one thread bins faster
constexpr uint32_t kParallelChildren = 2 * 1024;

/// A primitive's box and centroid stored together and moved by the partition, so every pass
/// over a node reads memory in order (no indirection through the id).
struct PrimRef {
  Bounds3 bounds;
  Vec3 centroid;
  uint32_t id;
};

struct Bin {
  Bounds3 bounds, centroids;
  uint32_t count = 0;
};

/// Bins of all three axes for one node; a parallel_reduce body.
struct Binning {
  std::array<std::array<Bin, kMaxBins>, 3> bins{};
  void add(int axis, int bin, const Bounds3& b, const Vec3& c) {
    Bin& x = bins[axis][bin];
    x.bounds.extend(b);
    x.centroids.extend(c);
    ++x.count;
  }
  void merge(const Binning& o) {
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < kMaxBins; ++i) {
        bins[a][i].bounds.extend(o.bins[a][i].bounds);
        bins[a][i].centroids.extend(o.bins[a][i].centroids);
        bins[a][i].count += o.bins[a][i].count;
      }
  }
};

class SahBuilder {
 public:
  SahBuilder(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options) : opt_(options) {
    opt_.bins = std::clamp(opt_.bins, 2, kMaxBins);
    opt_.maxLeafSize = std::clamp(opt_.maxLeafSize, 1, 255);
    for (uint32_t i = 0; i < bounds.size(); ++i) {
      const Bounds3& b = bounds[i];
      if (b.empty() || !b.finite()) continue;
      refs_.push_back({b, b.center(), i});
    }
  }

  Bvh build() {
    Bvh bvh;
    if (refs_.empty()) return bvh;
    nodes_.resize(2 * refs_.size());
    nodeCount_ = 1;
    Bounds3 b, cb;
    for (const PrimRef& r : refs_) b.extend(r.bounds), cb.extend(r.centroid);
    buildNode(0, 0, uint32_t(refs_.size()), b, cb);
    nodes_.resize(nodeCount_.load());
    nodes_.shrink_to_fit();
    bvh.nodes = std::move(nodes_);
    bvh.primitives.resize(refs_.size());
    for (size_t k = 0; k < refs_.size(); ++k) bvh.primitives[k] = refs_[k].id;
    return bvh;
  }

 private:
  void makeLeaf(uint32_t node, uint32_t begin, uint32_t end, const Bounds3& b) {
    BvhNode& n = nodes_[node];
    n.setBounds(b);
    n.offset = begin;
    n.count = uint16_t(end - begin);
    n.axis = 0;
    n.pad = 0;
  }

  int binOf(const Vec3& c, int axis, const Bounds3& cb, float scale) const {
    int i = int((c[axis] - cb.lo[axis]) * scale);
    return std::clamp(i, 0, opt_.bins - 1);
  }

  Binning binRange(uint32_t begin, uint32_t end, const Bounds3& cb, const Vec3& scale) const {
    auto body = [&](const tbb::blocked_range<uint32_t>& r, Binning acc) {
      for (uint32_t k = r.begin(); k < r.end(); ++k) {
        const PrimRef& ref = refs_[k];
        for (int a = 0; a < 3; ++a)
          acc.add(a, binOf(ref.centroid, a, cb, scale[a]), ref.bounds, ref.centroid);
      }
      return acc;
    };
    if (end - begin < kParallelBinning) return body({begin, end}, Binning{});
    return tbb::parallel_reduce(tbb::blocked_range<uint32_t>(begin, end, 8192), Binning{}, body,
                                [](Binning x, const Binning& y) {
                                  x.merge(y);
                                  return x;
                                });
  }

  void buildNode(uint32_t node, uint32_t begin, uint32_t end, const Bounds3& b, const Bounds3& cb) {
    const uint32_t n = end - begin;
    if (n == 1) return makeLeaf(node, begin, end, b);
    Vec3 extent = cb.diagonal();
    if (maxComponent(extent) <= 0.0f) {
      // All centroids coincide: no plane separates them. Split the range in half.
      if (n <= uint32_t(opt_.maxLeafSize)) return makeLeaf(node, begin, end, b);
      return splitAt(node, begin, begin + n / 2, end, b, int(0));
    }
    Vec3 scale;
    for (int a = 0; a < 3; ++a)
      scale[a] = extent[a] > 0 ? float(opt_.bins) * (1.0f - 1e-6f) / extent[a] : 0.0f;
    Binning binning = binRange(begin, end, cb, scale);

    // Sweep each axis: right-to-left accumulated areas, then left-to-right to evaluate planes.
    float bestCost = kInfinity;
    int bestAxis = -1, bestPlane = 0;
    for (int a = 0; a < 3; ++a) {
      if (extent[a] <= 0) continue;
      const auto& bins = binning.bins[a];
      std::array<float, kMaxBins> rightArea{};
      std::array<uint32_t, kMaxBins> rightCount{};
      Bounds3 acc;
      uint32_t count = 0;
      for (int i = opt_.bins - 1; i > 0; --i) {
        acc.extend(bins[i].bounds);
        count += bins[i].count;
        rightArea[i] = acc.surfaceArea();
        rightCount[i] = count;
      }
      acc = Bounds3();
      count = 0;
      for (int i = 0; i < opt_.bins - 1; ++i) {
        acc.extend(bins[i].bounds);
        count += bins[i].count;
        if (count == 0 || rightCount[i + 1] == 0) continue;
        float cost = acc.surfaceArea() * float(count) + rightArea[i + 1] * float(rightCount[i + 1]);
        if (cost < bestCost) bestCost = cost, bestAxis = a, bestPlane = i;
      }
    }
    float area = b.surfaceArea();
    float splitCost =
        opt_.traversalCost + opt_.intersectionCost * bestCost / std::max(area, 1e-30f);
    float leafCost = opt_.intersectionCost * float(n);
    if (n <= uint32_t(opt_.maxLeafSize) && leafCost <= splitCost)
      return makeLeaf(node, begin, end, b);
    if (bestAxis < 0) {
      // Every centroid fell into one bin on every axis: fall back to an object median.
      int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
      uint32_t mid = begin + n / 2;
      std::nth_element(
          refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
          [&](const PrimRef& x, const PrimRef& y) { return x.centroid[axis] < y.centroid[axis]; });
      return splitAt(node, begin, mid, end, b, axis);
    }
    const Bounds3& cbRef = cb;
    float s = scale[bestAxis];
    auto it = std::partition(refs_.begin() + begin, refs_.begin() + end, [&](const PrimRef& r) {
      return binOf(r.centroid, bestAxis, cbRef, s) <= bestPlane;
    });
    Bounds3 lb, lcb, rb, rcb;
    for (int i = 0; i < opt_.bins; ++i) {
      const Bin& x = binning.bins[bestAxis][i];
      (i <= bestPlane ? lb : rb).extend(x.bounds);
      (i <= bestPlane ? lcb : rcb).extend(x.centroids);
    }
    uint32_t mid = uint32_t(it - refs_.begin());
    children(node, begin, mid, end, b, bestAxis, lb, lcb, rb, rcb);
  }

  /// Splits [begin, end) at mid without bin information: recomputes the children's bounds.
  void splitAt(uint32_t node, uint32_t begin, uint32_t mid, uint32_t end, const Bounds3& b,
               int axis) {
    Bounds3 lb, lcb, rb, rcb;
    for (uint32_t k = begin; k < mid; ++k)
      lb.extend(refs_[k].bounds), lcb.extend(refs_[k].centroid);
    for (uint32_t k = mid; k < end; ++k) rb.extend(refs_[k].bounds), rcb.extend(refs_[k].centroid);
    children(node, begin, mid, end, b, axis, lb, lcb, rb, rcb);
  }

  void children(uint32_t node, uint32_t begin, uint32_t mid, uint32_t end, const Bounds3& b,
                int axis, const Bounds3& lb, const Bounds3& lcb, const Bounds3& rb,
                const Bounds3& rcb) {
    uint32_t first = nodeCount_.fetch_add(2);
    BvhNode& n = nodes_[node];
    n.setBounds(b);
    n.offset = first;
    n.count = 0;
    n.axis = uint8_t(axis);
    n.pad = 0;
    auto left = [&] { buildNode(first, begin, mid, lb, lcb); };
    auto right = [&] { buildNode(first + 1, mid, end, rb, rcb); };
    if (end - begin >= kParallelChildren) {
      tbb::parallel_invoke(left, right);
    } else {
      left();
      right();
    }
  }

  BvhBuildOptions opt_;
  std::vector<PrimRef> refs_;
  std::vector<BvhNode> nodes_;
  std::atomic<uint32_t> nodeCount_{0};
};

}  // namespace

Bvh buildBvhBinnedSah(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options) {
  return SahBuilder(bounds, options).build();
}

}  // namespace tray

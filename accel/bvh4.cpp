#include "accel/bvh4.h"

#include <cmath>

#include "core/error.h"

namespace tray {
namespace {

class Collapser {
 public:
  Collapser(const Bvh& bvh, Bvh4& out) : in_(bvh.nodes), out_(out) {}

  /// The 4-wide nodes fill makes from the binary subtree rooted at `binary` (so that the result
  /// is allocated once, at its size: reserving a guess and shrinking held both the guess and the
  /// copy at the peak, 66 MiB over the tree for 10^6 instances, bench/instancing_bench).
  size_t count(uint32_t binary) const {
    uint32_t kids[4];
    const int n = children(binary, kids);
    size_t nodes = 1;
    for (int c = 0; c < n; ++c)
      if (!in_[kids[c]].leaf()) nodes += count(kids[c]);
    return nodes;
  }

  /// Fills out_.nodes[node] from the binary subtree rooted at `binary`.
  void fill(uint32_t node, uint32_t binary) {
    uint32_t kids[4];
    const int n = children(binary, kids);
    for (int c = 0; c < 4; ++c) {
      Bvh4Node& o = out_.nodes[node];
      if (c >= n) {
        for (int a = 0; a < 3; ++a) o.lo[a][c] = INFINITY, o.hi[a][c] = -INFINITY;
        o.child[c] = bvh4ref::kEmpty;
        continue;
      }
      const BvhNode& k = in_[kids[c]];
      for (int a = 0; a < 3; ++a) o.lo[a][c] = k.lo[a], o.hi[a][c] = k.hi[a];
      if (k.leaf()) {
        if (k.count > bvh4ref::kMaxLeafItems || k.offset > bvh4ref::kMaxFirst)
          throw Error("BVH leaf too large for the 4-wide layout", Error::Kind::kRender);
        o.child[c] = bvh4ref::makeLeaf(k.offset, k.count);
      } else {
        uint32_t index = uint32_t(out_.nodes.size());
        out_.nodes.emplace_back();  // invalidates o
        out_.nodes[node].child[c] = index;
        fill(index, kids[c]);
      }
    }
  }

 private:
  /// The binary nodes that become the 4-wide node of `binary`: its children, the interior one
  /// of largest area opened until four (the one most rays enter); returns how many.
  int children(uint32_t binary, uint32_t kids[4]) const {
    int n = 0;
    const BvhNode& b = in_[binary];
    if (b.leaf()) {
      kids[n++] = binary;
    } else {
      kids[n++] = b.offset;
      kids[n++] = b.offset + 1;
    }
    while (n < 4) {
      int best = -1;
      float bestArea = -1;
      for (int i = 0; i < n; ++i) {
        const BvhNode& k = in_[kids[i]];
        float a = k.bounds().surfaceArea();
        if (!k.leaf() && a > bestArea) best = i, bestArea = a;
      }
      if (best < 0) break;
      uint32_t open = kids[best];
      for (int i = n; i > best + 1; --i) kids[i] = kids[i - 1];  // keep left-to-right order
      kids[best] = in_[open].offset;
      kids[best + 1] = in_[open].offset + 1;
      ++n;
    }
    return n;
  }

  const std::vector<BvhNode>& in_;
  Bvh4& out_;
};

}  // namespace

Bvh4 collapseToBvh4(Bvh bvh) {
  Bvh4 out;
  out.primitives = std::move(bvh.primitives);
  if (bvh.nodes.empty()) return out;
  Collapser collapser(bvh, out);
  out.nodes.reserve(collapser.count(0));  // exactly: no shrinking copy
  out.nodes.emplace_back();
  collapser.fill(0, 0);
  return out;
}

}  // namespace tray

#include "accel/bvh4.h"

#include <cmath>

#include "core/error.h"

namespace tray {
namespace {

class Collapser {
 public:
  Collapser(const Bvh& bvh, Bvh4& out) : in_(bvh.nodes), out_(out) {}

  /// Fills out_.nodes[node] from the binary subtree rooted at `binary`.
  void fill(uint32_t node, uint32_t binary) {
    uint32_t kids[4];
    int n = 0;
    const BvhNode& b = in_[binary];
    if (b.leaf()) {
      kids[n++] = binary;
    } else {
      kids[n++] = b.offset;
      kids[n++] = b.offset + 1;
    }
    // Open the interior child of largest area until four children: the one most rays enter.
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
  const std::vector<BvhNode>& in_;
  Bvh4& out_;
};

}  // namespace

Bvh4 collapseToBvh4(Bvh bvh) {
  Bvh4 out;
  out.primitives = std::move(bvh.primitives);
  if (bvh.nodes.empty()) return out;
  out.nodes.reserve(bvh.nodes.size() / 3 + 1);
  out.nodes.emplace_back();
  Collapser(bvh, out).fill(0, 0);
  out.nodes.shrink_to_fit();
  return out;
}

}  // namespace tray

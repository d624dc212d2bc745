// Incremental construction: Goldsmith & Salmon, "Automatic Creation of Object Hierarchies for
// Ray Tracing" (IEEE CG&A 1987), the seed's builder, kept to compare tree quality and speed with
// binned SAH. Primitives are inserted one at a time, in random order as the paper advises; each
// goes down the tree towards the child whose surface area grows least, and becomes the sibling
// of the node where that is cheaper than descending (the greedy cost of Catto's Box2D dynamic
// tree, which is Goldsmith–Salmon's area-increase rule). Ancestors are refitted on the way up.
#include <algorithm>
#include <numeric>
#include <random>

#include "accel/bvh.h"

namespace tray {
namespace {

constexpr int kNone = -1;
constexpr int kMaxDepth = 250;  // traversal stacks assume under 256 levels (accel/bvh4_traversal.h)

struct GsNode {
  Bounds3 bounds;
  int parent = kNone;
  int child[2] = {kNone, kNone};
  uint32_t primitive = 0;
  bool leaf() const { return child[0] == kNone; }
};

Bounds3 merged(const Bounds3& a, const Bounds3& b) {
  Bounds3 m = a;
  m.extend(b);
  return m;
}

class GoldsmithSalmonBuilder {
 public:
  explicit GoldsmithSalmonBuilder(const std::vector<Bounds3>& bounds) : bounds_(bounds) {}

  Bvh build() {
    std::vector<uint32_t> order;
    for (uint32_t i = 0; i < bounds_.size(); ++i)
      if (!bounds_[i].empty() && bounds_[i].finite()) order.push_back(i);
    std::mt19937 rng(20240601u);  // fixed: the same scene always gives the same tree
    std::shuffle(order.begin(), order.end(), rng);
    nodes_.reserve(2 * order.size());
    for (uint32_t id : order) insert(id);
    return flatten();
  }

  bool tooDeep() const { return depth_ > kMaxDepth; }

 private:
  int newNode() {
    nodes_.emplace_back();
    return int(nodes_.size() - 1);
  }

  void insert(uint32_t id) {
    const Bounds3& pb = bounds_[id];
    int leaf = newNode();
    nodes_[leaf].bounds = pb;
    nodes_[leaf].primitive = id;
    if (root_ == kNone) {
      root_ = leaf;
      return;
    }
    // Descend while moving the new primitive further down is cheaper than pairing it here.
    int node = root_;
    while (!nodes_[node].leaf()) {
      const GsNode& n = nodes_[node];
      float area = n.bounds.surfaceArea();
      float combined = merged(n.bounds, pb).surfaceArea();
      float pairHere = 2.0f * combined;            // a new parent of `node` and the leaf
      float inherited = 2.0f * (combined - area);  // every ancestor below grows this much
      float childCost[2];
      for (int c = 0; c < 2; ++c) {
        const GsNode& ch = nodes_[n.child[c]];
        float grown = merged(ch.bounds, pb).surfaceArea();
        childCost[c] = inherited + (ch.leaf() ? grown : grown - ch.bounds.surfaceArea());
      }
      if (pairHere < childCost[0] && pairHere < childCost[1]) break;
      node = n.child[childCost[1] < childCost[0] ? 1 : 0];
    }
    // Pair `node` with the new leaf under a new parent.
    int oldParent = nodes_[node].parent;
    int parent = newNode();
    nodes_[parent].parent = oldParent;
    nodes_[parent].bounds = merged(nodes_[node].bounds, pb);
    nodes_[parent].child[0] = node;
    nodes_[parent].child[1] = leaf;
    nodes_[node].parent = parent;
    nodes_[leaf].parent = parent;
    if (oldParent == kNone) {
      root_ = parent;
    } else {
      GsNode& op = nodes_[oldParent];
      op.child[op.child[0] == node ? 0 : 1] = parent;
    }
    for (int a = oldParent; a != kNone; a = nodes_[a].parent) nodes_[a].bounds.extend(pb);
  }

  /// Depth-first copy into the flattened layout, children in consecutive pairs.
  Bvh flatten() {
    Bvh bvh;
    if (root_ == kNone) return bvh;
    bvh.nodes.reserve(nodes_.size());
    bvh.nodes.emplace_back();
    struct Item {
      int src;
      uint32_t dst;
      int depth;
    };
    std::vector<Item> stack{{root_, 0, 0}};
    while (!stack.empty()) {
      Item it = stack.back();
      stack.pop_back();
      depth_ = std::max(depth_, it.depth);
      const GsNode& n = nodes_[it.src];
      BvhNode out{};
      out.setBounds(n.bounds);
      if (n.leaf()) {
        out.offset = uint32_t(bvh.primitives.size());
        out.count = 1;
        bvh.primitives.push_back(n.primitive);
      } else {
        out.offset = uint32_t(bvh.nodes.size());
        Vec3 d = nodes_[n.child[1]].bounds.center() - nodes_[n.child[0]].bounds.center();
        Vec3 ad = abs(d);
        out.axis = uint8_t(ad.x >= ad.y && ad.x >= ad.z ? 0 : (ad.y >= ad.z ? 1 : 2));
        // Order the pair along that axis so front-to-back traversal can use the sign of the ray.
        int first = d[out.axis] >= 0 ? 0 : 1;
        bvh.nodes.emplace_back();
        bvh.nodes.emplace_back();
        stack.push_back({n.child[first], out.offset, it.depth + 1});
        stack.push_back({n.child[1 - first], out.offset + 1, it.depth + 1});
      }
      bvh.nodes[it.dst] = out;
    }
    return bvh;
  }

  const std::vector<Bounds3>& bounds_;
  std::vector<GsNode> nodes_;
  int root_ = kNone;
  int depth_ = 0;
};

}  // namespace

Bvh buildBvhGoldsmithSalmon(const std::vector<Bounds3>& bounds, const BvhBuildOptions& options) {
  GoldsmithSalmonBuilder builder(bounds);
  Bvh bvh = builder.build();
  // Insertion order can, rarely, grow a chain deeper than the traversal stack: rebuild those few
  // trees top-down rather than give traversal an unbounded stack.
  if (builder.tooDeep()) return buildBvhBinnedSah(bounds, options);
  return bvh;
}

}  // namespace tray

#pragma once
// The traversal layout: a 4-wide BVH (Ernst & Greiner 2008; Wald et al., "Getting Rid of
// Packets", 2008; Embree's BVH4) made by collapsing a binary tree from accel/bvh.h. One node
// holds the boxes of its four children as structure-of-arrays, so a ray tests all four with one
// instruction per slab (accel/bvh4_traversal.h), and a tree has a third as many nodes to visit.
#include <cstdint>
#include <vector>

#include "accel/bvh.h"

namespace tray {

/// A child reference: an interior node's index, or a leaf (kLeafBit) of `count` items starting
/// at `first`, packed as kLeafBit | first << 4 | (count - 1).
namespace bvh4ref {
constexpr uint32_t kLeafBit = 1u << 31;
constexpr uint32_t kEmpty = 0xffffffffu;  ///< unused child slot (its box is empty)
constexpr uint32_t kMaxLeafItems = 16;
constexpr uint32_t kMaxFirst = (1u << 27) - 1;
inline bool leaf(uint32_t ref) {
  return ref & kLeafBit;
}
inline uint32_t first(uint32_t ref) {
  return (ref & ~kLeafBit) >> 4;
}
inline uint32_t count(uint32_t ref) {
  return (ref & 15u) + 1;
}
inline uint32_t makeLeaf(uint32_t first, uint32_t count) {
  return kLeafBit | first << 4 | (count - 1);
}
}  // namespace bvh4ref

/// 128 bytes: two cache lines. Empty slots have lo = +inf, hi = -inf, which no slab test enters.
struct alignas(64) Bvh4Node {
  float lo[3][4];  ///< [axis][child]
  float hi[3][4];
  uint32_t child[4];
  uint32_t pad[4];
};
static_assert(sizeof(Bvh4Node) == 128);

/// Node 0 is the root (an interior node, even over a single leaf). Leaf items are whatever the
/// binary tree's leaves indexed (Bvh::primitives positions) until a user renumbers them
/// (accel/bvh_mesh.cpp turns them into blocks of four triangles).
struct Bvh4 {
  std::vector<Bvh4Node> nodes;
  std::vector<uint32_t> primitives;  ///< the binary tree's primitive ids, in leaf order
  size_t memoryBytes() const {
    return nodes.capacity() * sizeof(Bvh4Node) + primitives.capacity() * sizeof(uint32_t);
  }
};

/// Collapses a binary tree: each 4-wide node takes the children of up to three binary nodes,
/// opening the child of largest surface area first (Embree's BVHNBuilder). Leaves keep their
/// primitive ranges (at most bvh4ref::kMaxLeafItems each: builders clamp maxLeafSize).
Bvh4 collapseToBvh4(Bvh bvh);

}  // namespace tray

#include "accel/bvh_mesh.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "accel/bvh4_traversal.h"
#include "core/motion.h"

namespace tray {
namespace {

void vertices(const TriangleMesh& m, const std::vector<Vec3>& positions, uint32_t tri, Vec3& p0,
              Vec3& p1, Vec3& p2) {
  p0 = positions[m.indices[3 * tri]];
  p1 = positions[m.indices[3 * tri + 1]];
  p2 = positions[m.indices[3 * tri + 2]];
}

/// Packs up to four triangles (ids[0..n)) with their vertices at `positions` into a block; the
/// other lanes stay empty.
Triangle4 pack(const TriangleMesh& m, const std::vector<Vec3>& positions, const uint32_t* ids,
               uint32_t n) {
  Triangle4 b;
  for (int lane = 0; lane < 4; ++lane) {
    Vec3 p[3];
    b.index[lane] = Triangle4::kNoTriangle;
    for (Vec3& q : p) q = Vec3(NAN);
    if (uint32_t(lane) < n) {
      b.index[lane] = ids[lane];
      vertices(m, positions, ids[lane], p[0], p[1], p[2]);
    }
    for (int v = 0; v < 3; ++v)
      for (int a = 0; a < 3; ++a) b.p[v][a][lane] = p[v][a];
  }
  return b;
}

}  // namespace

void MeshBvh::pushBlock(const uint32_t* ids, uint32_t n) {
  blocks_.push_back(pack(mesh_, mesh_.positions, ids, n));
  for (size_t k = 0; k < stepBlocks_.size(); ++k)
    stepBlocks_[k].push_back(pack(mesh_, mesh_.positionSteps[k], ids, n));
}

Triangle4 MeshBvh::blockAt(size_t segment, float f, uint32_t k) const {
  // Embree's vertex motion: each vertex interpolated linearly within the time segment.
  const Triangle4 &a = stepBlocks_[segment][k], &b = stepBlocks_[segment + 1][k];
  Triangle4 out;
  for (int v = 0; v < 3; ++v)
    for (int axis = 0; axis < 3; ++axis)
      for (int lane = 0; lane < 4; ++lane)
        out.p[v][axis][lane] = (1.0f - f) * a.p[v][axis][lane] + f * b.p[v][axis][lane];
  for (int lane = 0; lane < 4; ++lane) out.index[lane] = a.index[lane];
  return out;
}

MeshBvh::MeshBvh(const TriangleMesh& mesh, const BvhBuildOptions& options, bool hierarchy)
    : mesh_(mesh), stepBlocks_(mesh.positionSteps.size()), hierarchy_(hierarchy) {
  const uint32_t n = uint32_t(mesh.triangleCount());
  std::vector<Bounds3> boxes(n);
  // A deforming mesh: each triangle boxed over every step (a vertex moves linearly between two
  // steps, so the union holds the triangle at any time), as Embree's motion-blur boxes do.
  std::vector<const std::vector<Vec3>*> steps;
  for (const auto& step : mesh.positionSteps) steps.push_back(&step);
  if (steps.empty()) steps.push_back(&mesh.positions);
  tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 16384), [&](const auto& r) {
    for (uint32_t i = r.begin(); i < r.end(); ++i) {
      Bounds3 b;
      for (const std::vector<Vec3>* positions : steps) {
        Vec3 p0, p1, p2;
        vertices(mesh, *positions, i, p0, p1, p2);
        b.extend(p0);
        b.extend(p1);
        b.extend(p2);
      }
      boxes[i] = b;
    }
  });
  std::vector<uint32_t> usable;
  for (uint32_t i = 0; i < n; ++i)
    if (boxes[i].finite()) bounds_.extend(boxes[i]), usable.push_back(i);
  triangleCount_ = usable.size();
  if (!hierarchy_) {
    for (size_t k = 0; k < usable.size(); k += 4)
      pushBlock(&usable[k], uint32_t(std::min<size_t>(4, usable.size() - k)));
    return;
  }
  // Leaves are tested four triangles at a time: the SAH counts blocks, so leaves fill them, and
  // may hold two blocks (measured in bench/accel_bench: a smaller tree, fewer cache misses on
  // incoherent rays, than leaves of one block, though the SAH cost is a little higher).
  BvhBuildOptions blocked = options;
  blocked.blockSize = 4;
  blocked.maxLeafSize = 2 * blocked.blockSize;
  Bvh binary = buildBvh(boxes, blocked);
  sahCost_ = tray::sahCost(binary, options);
  binaryNodes_ = binary.nodes.size();
  bvh_ = collapseToBvh4(std::move(binary));
  // Renumber the leaves: from ranges of bvh_.primitives to ranges of blocks of four triangles,
  // stored in the order the leaves appear (children of one node sit together in memory).
  size_t leafTriangles = 0;
  for (const Bvh4Node& node : bvh_.nodes)
    for (uint32_t ref : node.child)
      if (ref != bvh4ref::kEmpty && bvh4ref::leaf(ref)) leafTriangles += bvh4ref::count(ref);
  blocks_.reserve(leafTriangles / 2);
  for (Bvh4Node& node : bvh_.nodes)
    for (uint32_t& ref : node.child) {
      if (ref == bvh4ref::kEmpty || !bvh4ref::leaf(ref)) continue;
      const uint32_t first = bvh4ref::first(ref), count = bvh4ref::count(ref);
      const uint32_t firstBlock = uint32_t(blocks_.size());
      for (uint32_t k = 0; k < count; k += 4)
        pushBlock(&bvh_.primitives[first + k], std::min(4u, count - k));
      ref = bvh4ref::makeLeaf(firstBlock, uint32_t(blocks_.size()) - firstBlock);
    }
  blocks_.shrink_to_fit();
  bvh_.primitives = {};  // the blocks carry the triangle indices
}

template <bool kOrdered, class OnBlock>
bool MeshBvh::forEachBlock(const Ray& ray, const float& tmax, OnBlock&& onBlock) const {
  if (stepBlocks_.empty())
    return traverseBlocks<kOrdered>(
        ray, tmax, [&](uint32_t k) -> const Triangle4& { return blocks_[k]; }, onBlock);
  // A deforming mesh: each block interpolated at the ray's time before the test. A getter of
  // its own, so that static meshes run the loop they ran before motion blur existed.
  size_t segment = 0;
  float f = 0;
  timeSegment(stepBlocks_.size(), ray.time, segment, f);
  return traverseBlocks<kOrdered>(
      ray, tmax, [&](uint32_t k) { return blockAt(segment, f, k); }, onBlock);
}

/// The blocks of the leaves the ray enters, each as `block(k)` gives it, tested against the
/// ray; `onBlock` sees the hits of each and returns true to stop.
template <bool kOrdered, class BlockOf, class OnBlock>
bool MeshBvh::traverseBlocks(const Ray& ray, const float& tmax, BlockOf&& blockOf,
                             OnBlock&& onBlock) const {
  const WatertightRay4 wr = prepareWatertight4(ray.o, ray.d);
  auto leaf = [&](uint32_t first, uint32_t count) {
    for (uint32_t k = first; k < first + count; ++k) {
      decltype(auto) block = blockOf(k);  // a reference to a stored block, or a made one
      alignas(16) float t[4], b1[4], b2[4];
      int mask = intersectWatertight4(wr, block, ray.tmin, tmax, t, b1, b2);
      if (mask && onBlock(block, mask, t, b1, b2)) return true;
    }
    return false;
  };
  if (!hierarchy_) return leaf(0, uint32_t(blocks_.size()));
  return traverseBvh4<kOrdered>(bvh_, prepareBvh4Ray(ray.o, ray.d), ray.tmin, tmax, leaf);
}

/// The closest accepted hit: `accept(triangle, b1, b2)` is inlined, so the opaque loop (accept
/// always true) costs what it did before alpha testing existed.
template <class Accept>
[[gnu::always_inline]] inline bool MeshBvh::closestHit(const Ray& ray, float& tmax, Hit& hit,
                                                       const Accept& accept) const {
  bool found = false;
  forEachBlock<true>(
      ray, tmax,
      [&](const Triangle4& block, int mask, const float* t, const float* b1, const float* b2) {
        found |= closestLane(block, mask, t, b1, b2, tmax, hit, accept);
        return false;
      });
  return found;
}

[[gnu::flatten]] bool MeshBvh::intersect(const Ray& ray, float& tmax, Hit& hit) const {
  return closestHit(ray, tmax, hit, [](uint32_t, float, float) { return true; });
}

[[gnu::flatten]] bool MeshBvh::occluded(const Ray& ray, uint32_t& block) const {
  // Any hit will do: children in slot order, no sorting (measured faster, bench/accel_bench).
  return forEachBlock<false>(
      ray, ray.tmax, [&](const Triangle4& b, int, const float*, const float*, const float*) {
        // A deforming mesh's block was made for this ray: none for the last-occluder cache.
        block = stepBlocks_.empty() ? uint32_t(&b - blocks_.data()) : uint32_t(blocks_.size());
        return true;
      });
}

bool MeshBvh::intersect(const Ray& ray, float& tmax, Hit& hit, const TriangleFilter& filter) const {
  return closestHit(ray, tmax, hit, [&](uint32_t triangle, float b1, float b2) {
    return filter.accept(filter.data, triangle, b1, b2);
  });
}

bool MeshBvh::occluded(const Ray& ray, const TriangleFilter& filter) const {
  return forEachBlock<false>(
      ray, ray.tmax,
      [&](const Triangle4& block, int mask, const float*, const float* b1, const float* b2) {
        return anyLaneAccepted(block, mask, b1, b2, [&](uint32_t triangle, float u, float v) {
          return filter.accept(filter.data, triangle, u, v);
        });
      });
}

void MeshBvh::allHits(const Ray& ray, uint32_t primitive, std::vector<Hit>& hits) const {
  forEachBlock<true>(
      ray, ray.tmax,
      [&](const Triangle4& block, int mask, const float* t, const float* b1, const float* b2) {
        for (; mask; mask &= mask - 1) {
          int i = __builtin_ctz(unsigned(mask));
          Hit h;
          h.t = t[i];
          h.primitive = primitive;
          h.triangle = block.index[i];
          h.b1 = b1[i];
          h.b2 = b2[i];
          hits.push_back(h);
        }
        return false;
      });
}

bool MeshBvh::occludedBy(const Ray& ray, uint32_t block) const {
  if (block >= blocks_.size() || !stepBlocks_.empty()) return false;
  alignas(16) float t[4], b1[4], b2[4];
  return intersectWatertight4(prepareWatertight4(ray.o, ray.d), blocks_[block], ray.tmin, ray.tmax,
                              t, b1, b2) != 0;
}

}  // namespace tray

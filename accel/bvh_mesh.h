#pragma once
// The bottom level: one tree per TriangleMesh, built once and shared by every instance of it.
// Rays arrive in the mesh's object space (direction not normalised, so t is the world t), as
// with Embree's instances.
#include <cstdint>
#include <vector>

#include "accel/bvh.h"
#include "accel/bvh4.h"
#include "accel/bvh4_packet.h"
#include "accel/bvh_triangle4.h"
#include "core/hit.h"
#include "core/ray.h"
#include "core/triangle_mesh.h"

namespace tray {

/// An any-hit test on a mesh's triangles (alpha cut-outs, textures/alpha.h): false = the ray passes
/// through triangle `triangle` at barycentrics (b1, b2). A function pointer and its data rather
/// than a template, so that opaque meshes keep their own, unfiltered loops.
struct TriangleFilter {
  bool (*accept)(const void* data, uint32_t triangle, float b1, float b2);
  const void* data;
};

/// The rays of a packet in a mesh's object space, prepared once for the box and triangle tests
/// (the single-ray queries prepare the same values per query). Slot r holds ray r.
struct PacketRays {
  PacketBoxRay box[kMaxPacketRays];
  WatertightRay4 triangle[kMaxPacketRays];
  float tmin[kMaxPacketRays];
  void set(int r, const Ray& ray) {
    box[r] = PacketBoxRay(ray.o, ray.d);
    triangle[r] = prepareWatertight4(ray.o, ray.d);
    tmin[r] = ray.tmin;
  }
};

/// TriangleFilter for packets: false = ray `ray` of the packet passes through the triangle.
struct PacketTriangleFilter {
  bool (*accept)(const void* data, int ray, uint32_t triangle, float b1, float b2);
  const void* data;
};

class MeshBvh {
 public:
  /// hierarchy = false: no tree, every query tests every triangle (the naive accelerator).
  /// The tree is built with options' builder, bins and costs; block size 4 and leaves of up to
  /// 8 triangles are fixed by the leaf layout (accel/bvh_mesh.cpp).
  MeshBvh(const TriangleMesh& mesh, const BvhBuildOptions& options, bool hierarchy = true);

  /// Closest triangle with t in (ray.tmin, tmax); lowers tmax and fills hit's mesh fields.
  bool intersect(const Ray& ray, float& tmax, Hit& hit) const;
  /// Any triangle with t in (ray.tmin, ray.tmax); the index of its block goes to `block`.
  bool occluded(const Ray& ray, uint32_t& block) const;
  /// The same two queries with an any-hit test: rejected triangles neither end nor shorten them.
  bool intersect(const Ray& ray, float& tmax, Hit& hit, const TriangleFilter& filter) const;
  bool occluded(const Ray& ray, const TriangleFilter& filter) const;
  /// Appends every triangle hit in (ray.tmin, ray.tmax), tagged with `primitive`.
  void allHits(const Ray& ray, uint32_t primitive, std::vector<Hit>& hits) const;
  /// Tests one block of four triangles (the last-occluder cache). The block, not the mesh's own
  /// triangle, since the block was just read by the previous ray and is likely still cached:
  /// reading the mesh's index and vertex arrays instead costs more than the cache saves.
  bool occludedBy(const Ray& ray, uint32_t block) const;

  /// Packets (accel/bvh4_packet.h; static meshes only, !deforming()). Closest hits of the rays
  /// in `active`: where ray r meets a triangle before tmax[r], lowers tmax[r], fills hits[r] as
  /// intersect() does and sets bit r of the result. Each ray gets its intersect() hit (the
  /// same arithmetic), up to which of several triangles at exactly equal t is reported.
  RayMask intersectPacket(const PacketRays& rays, RayMask active, float* tmax, Hit* hits,
                          const PacketTriangleFilter* filter = nullptr) const;
  /// Clears from `alive` the rays of `active` (a subset) blocked within (tmin, tmax[r]); the
  /// index of the block that blocked the highest-numbered of them goes to `block` (for
  /// occludedBy: the next packet's first rays are that ray's neighbours).
  void occludedPacket(const PacketRays& rays, RayMask active, RayMask& alive, const float* tmax,
                      uint32_t& block, const PacketTriangleFilter* filter = nullptr) const;
  /// Triangles move (TriangleMesh::positionSteps): packets do not apply.
  bool deforming() const { return !stepBlocks_.empty(); }

  Bounds3 bounds() const { return bounds_; }
  /// The binary tree's SAH cost (before collapsing to 4-wide), its node and triangle counts.
  double sahCost() const { return sahCost_; }
  size_t binaryNodes() const { return binaryNodes_; }
  size_t triangles() const { return triangleCount_; }
  const Bvh4& tree() const { return bvh_; }
  size_t memoryBytes() const {
    return bvh_.memoryBytes() + blocks_.capacity() * (1 + stepBlocks_.size()) * sizeof(Triangle4);
  }

 private:
  template <class Accept>
  bool closestHit(const Ray& ray, float& tmax, Hit& hit, const Accept& accept) const;
  template <class Accept>
  RayMask closestHitPacket(const PacketRays& rays, RayMask active, float* tmax, Hit* hits,
                           const Accept& accept) const;
  template <class OnBlock>
  void anyHitPacket(const PacketRays& rays, RayMask active, RayMask& alive, const float* tmax,
                    uint32_t& blocker, OnBlock&& onBlock) const;
  template <bool kOrdered, class OnBlock>
  bool forEachBlock(const Ray& ray, const float& tmax, OnBlock&& onBlock) const;
  template <bool kOrdered, class BlockOf, class OnBlock>
  bool traverseBlocks(const Ray& ray, const float& tmax, BlockOf&& blockOf,
                      OnBlock&& onBlock) const;
  /// Appends the block of triangles ids[0..n) to blocks_ and, for a deforming mesh, to every
  /// step's blocks.
  void pushBlock(const uint32_t* ids, uint32_t n);
  /// Block k of a deforming mesh at `f` of the way through time segment `segment`.
  Triangle4 blockAt(size_t segment, float f, uint32_t k) const;

  Bvh4 bvh_;  ///< leaves index blocks_
  const TriangleMesh& mesh_;
  std::vector<Triangle4> blocks_;  ///< leaf by leaf (or every triangle, without hierarchy)
  /// A deforming mesh (TriangleMesh::positionSteps): blocks_ at each motion step; else empty.
  std::vector<std::vector<Triangle4>> stepBlocks_;
  Bounds3 bounds_;
  bool hierarchy_;
  double sahCost_ = 0;
  size_t binaryNodes_ = 0, triangleCount_ = 0;
};

}  // namespace tray

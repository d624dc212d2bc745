// Two levels, as Embree's instances: the top tree holds placed primitives by world bounds; a
// mesh instance transforms the ray into object space (t unchanged, the direction is not
// normalised) and descends into its mesh's tree. Analytic shapes (spheres, boxes, CSG) are top
// level leaves tested through Scene::intersectShape; unbounded ones (planes, half-spaces) sit
// beside the tree and are tested by every ray.
#include "accel/bvh_accelerator.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

#include "accel/bvh4_traversal.h"
#include "accel/bvh_batch.h"
#include "accel/bvh_mesh.h"
#include "accel/bvh_object_ray.h"
#include "accel/bvh_top_level.h"
#include "accel/embree_only.h"
#include "accel/shape_crossings.h"
#include "core/motion.h"
#include "core/scene.h"
#include "textures/alpha.h"

namespace tray {
namespace {

std::atomic<uint64_t> gNextAcceleratorId{1};

/// The seed's shadow-ray cache: the primitive (and block of four triangles) that blocked this
/// thread's last
/// shadow ray is tested first, since neighbouring shading points are usually blocked by the same
/// occluder. Keyed by accelerator id so a stale entry of another accelerator is never used.
struct LastOccluder {
  uint64_t accelerator = 0;
  uint32_t primitive = kNoPrimitive;  ///< the item (TwoLevelParts::placed)
  uint32_t member = 0;  ///< which instance of an instance array's group: the first is 0
  uint32_t block = 0;   ///< MeshBvh block index (meshes only)
};
thread_local LastOccluder tLastOccluder;

class TwoLevelAccelerator final : public Accelerator, TwoLevelParts {
 public:
  TwoLevelAccelerator(const Scene& scene, const TwoLevelOptions& options)
      : scene_(scene), options_(options), id_(gNextAcceleratorId++) {
    const auto& prims = scene.primitives;
    std::vector<uint32_t> used;
    std::vector<char> isUsed(scene.meshes.size(), 0);
    for (const Primitive& p : prims)
      if (p.kind == Primitive::Kind::kMesh && !isUsed[p.mesh])
        isUsed[p.mesh] = 1, used.push_back(p.mesh);
    meshes_.resize(scene.meshes.size());
    alphaTested_.resize(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m)
      alphaTested_[m] = needsAlphaTest(scene.material(scene.meshes[m].material));
    tbb::parallel_for(size_t(0), used.size(), [&](size_t k) {
      uint32_t m = used[k];
      meshes_[m] = std::make_unique<MeshBvh>(scene.meshes[m], options.build, options.hierarchy);
    });
    top_ = buildTopLevel(scene, meshes_, options, *this);
    // What the batched queries read (accel/bvh_batch.h).
    TwoLevelParts::scene = &scene_;
    top = &top_.tree;
    meshes = &meshes_;
    alphaTested = &alphaTested_;
    unbounded = &top_.unbounded;
    single = top_.single;
  }

  bool intersect(const Ray& ray, Hit& hit) const override {
    float tmax = ray.tmax;
    bool found = false;
    forEachPrimitive(ray, tmax, [&](uint32_t i) {
      found |= intersectPrimitive(i, ray, tmax, hit);
      return false;
    });
    return found;
  }

  bool occluded(const Ray& ray) const override {
    if (occludedByCached(ray)) return true;
    uint32_t block = 0, member = 0;
    const float tmax = ray.tmax;
    return forEachPrimitive<false>(ray, tmax, [&](uint32_t i) {
      if (!occludedPrimitive(i, ray, member, block)) return false;
      cacheOccluder(i, member, block);
      return true;
    });
  }

  bool occludedByCached(const Ray& ray) const override {
    const LastOccluder& cache = tLastOccluder;
    return options_.occluderCache && cache.accelerator == id_ && cache.primitive < itemCount &&
           occludedBy(cache.primitive, cache.member, cache.block, ray);
  }

  void cacheOccluder(uint32_t i, uint32_t member, uint32_t block) const override {
    if (options_.occluderCache) tLastOccluder = {id_, i, member, block};
  }

  void intersectBatch(std::span<const Ray> rays, std::span<Hit> hits,
                      std::span<uint8_t> found) const override {
    if (!batched()) return Accelerator::intersectBatch(rays, hits, found);
    twoLevelIntersectBatch(*this, bvhBatchRays(options_.batch), byOctant(), rays, hits, found);
  }

  void occludedBatch(std::span<const Ray> rays, std::span<uint8_t> blocked) const override {
    if (!batched()) return Accelerator::occludedBatch(rays, blocked);
    twoLevelOccludedBatch(*this, bvhBatchRays(options_.batch), byOctant(), rays, blocked);
  }

  void allHits(const Ray& ray, std::vector<Hit>& hits) const override {
    hits.clear();
    const float tmax = ray.tmax;
    forEachPrimitive(ray, tmax, [&](uint32_t item) {
      const auto [i, first, count, boxes] = placed(item);
      const Primitive& p = scene_.primitives[i];
      if (p.kind == Primitive::Kind::kMesh) {
        for (uint32_t instance = first; instance < first + count; ++instance) {
          Ray local;
          const size_t before = hits.size();
          if (objectRay(p, instance, ray, ray.tmax, local))
            meshes_[p.mesh]->allHits(local, i, hits);
          for (size_t k = before; k < hits.size(); ++k) hits[k].instance = instance;
        }
      } else {
        // A named copy: a structured binding cannot be captured before C++20 P1091 (clang 16).
        const uint32_t primitive = i;
        forEachShapeCrossing(p, ray, [&](Hit& h) {
          h.primitive = primitive;
          hits.push_back(h);
        });
      }
      return false;
    });
    // Sorted as Embree's allHits; material last so that exact duplicates are adjacent.
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
      if (a.t != b.t) return a.t < b.t;
      if (a.primitive != b.primitive) return a.primitive < b.primitive;
      if (a.instance != b.instance) return a.instance < b.instance;
      if (a.triangle != b.triangle) return a.triangle < b.triangle;
      return a.material < b.material;
    });
    // A tangent ray reports a shape's enter and exit at one t: keep one, as Embree's filter does.
    hits.erase(std::unique(hits.begin(), hits.end(),
                           [](const Hit& a, const Hit& b) {
                             return a.t == b.t && a.primitive == b.primitive &&
                                    a.instance == b.instance && a.triangle == b.triangle &&
                                    a.material == b.material;
                           }),
               hits.end());
  }

  size_t memoryBytes() const override {
    size_t bytes = top_.tree.memoryBytes() +
                   (top_.unbounded.capacity() + top_.flat.capacity()) * sizeof(uint32_t);
    for (const auto& b : top_.arrayBoxes) bytes += b.capacity() * sizeof(InstanceBoxes4);
    for (const auto& m : meshes_)
      if (m) bytes += m->memoryBytes();
    return bytes;
  }

  BvhQuality quality() const {
    BvhQuality q;
    double weight = 0;
    for (const auto& m : meshes_)
      if (m) {
        q.meshSahCost += m->sahCost() * double(m->triangles());
        weight += double(m->triangles());
        q.nodes += m->binaryNodes();
        q.wideNodes += m->tree().nodes.size();
      }
    if (weight > 0) q.meshSahCost /= weight;
    q.topSahCost = top_.sahCost;
    q.nodes += top_.binaryNodes;
    q.wideNodes += top_.tree.nodes.size();
    return q;
  }

 private:
  /// Calls visit(i) for every primitive the ray may hit before tmax; stops when it returns true.
  template <bool kOrdered = true, class Visit>
  bool forEachPrimitive(const Ray& ray, const float& tmax, Visit&& visit) const {
    for (uint32_t i : top_.unbounded)
      if (visit(i)) return true;
    if (!options_.hierarchy) {
      for (uint32_t i : top_.flat)
        if (visit(i)) return true;
      return false;
    }
    if (top_.single != kNoPrimitive) return visit(top_.single);
    return traverseBvh4<kOrdered>(top_.tree, prepareBvh4Ray(ray.o, ray.d), ray.tmin, tmax,
                                  [&](uint32_t first, uint32_t count) {
                                    for (uint32_t k = first; k < first + count; ++k)
                                      if (visit(top_.tree.primitives[k])) return true;
                                    return false;
                                  });
  }

  bool batched() const { return options_.hierarchy && options_.batch != BvhBatch::kLoop; }
  bool byOctant() const { return options_.batch == BvhBatch::kStream64; }

  bool intersectPrimitive(uint32_t item, const Ray& ray, float& tmax, Hit& hit) const override {
    const Placed pl = placed(item);
    if (pl.boxes) {  // a group of an instance array's instances: those whose box the ray enters
      bool found = false;
      prefetchGroupMatrices(*scene_.primitives[pl.primitive].instances, pl.instance, pl.count);
      const Bvh4Ray r = prepareBvh4Ray(ray.o, ray.d);
      for (unsigned in = hitGroupBoxes(pl.boxes, kGroupBoxNodes, r, ray.tmin, tmax); in;
           in &= in - 1)
        found |= intersectInstance(
            pl.primitive, pl.instance + uint32_t(__builtin_ctz(unsigned(in))), ray, tmax, hit);
      return found;
    }
    return intersectInstance(pl.primitive, pl.instance, ray, tmax, hit);
  }

  /// The closest-hit query of primitive i (instance `instance` of an instance array).
  bool intersectInstance(uint32_t i, uint32_t instance, const Ray& ray, float& tmax,
                         Hit& hit) const {
    const Primitive& p = scene_.primitives[i];
    if (p.kind == Primitive::Kind::kMesh) {
      Hit h;
      Ray local;
      if (!objectRay(p, instance, ray, tmax, local)) return false;
      if (alphaTested_[p.mesh]) {
        const AlphaQuery q{scene_, ray, i};
        if (!meshes_[p.mesh]->intersect(local, tmax, h, q.filter())) return false;
        h.primitive = i;
        h.instance = instance;
        hit = h;
        return true;
      }
      if (!meshes_[p.mesh]->intersect(local, tmax, h)) return false;
      h.primitive = i;
      h.instance = instance;
      hit = h;
      return true;
    }
    Hit h;
    if (!scene_.intersectShape(i, Ray{ray.o, ray.d, ray.tmin, tmax, ray.blend, ray.time}, h))
      return false;
    tmax = h.t;
    hit = h;
    return true;
  }

  /// Any hit of item's primitive or group; `member` receives which instance of the group.
  bool occludedPrimitive(uint32_t item, const Ray& ray, uint32_t& member, uint32_t& block) const {
    const Placed pl = placed(item);
    member = 0;
    if (pl.boxes) {
      prefetchGroupMatrices(*scene_.primitives[pl.primitive].instances, pl.instance, pl.count);
      const Bvh4Ray r = prepareBvh4Ray(ray.o, ray.d);
      for (unsigned in = hitGroupBoxes(pl.boxes, kGroupBoxNodes, r, ray.tmin, ray.tmax); in;
           in &= in - 1) {
        member = uint32_t(__builtin_ctz(unsigned(in)));
        if (occludedInstance(pl.primitive, pl.instance + member, ray, block)) return true;
      }
      return false;
    }
    return occludedInstance(pl.primitive, pl.instance, ray, block);
  }

  bool occludedInstance(uint32_t i, uint32_t instance, const Ray& ray, uint32_t& block) const {
    const Primitive& p = scene_.primitives[i];
    block = 0;
    Ray local;
    if (p.kind == Primitive::Kind::kMesh && !objectRay(p, instance, ray, ray.tmax, local))
      return false;
    if (p.kind == Primitive::Kind::kMesh && alphaTested_[p.mesh]) {
      // block stays 0 and occludedBy refuses alpha-tested meshes: the cache never skips the test.
      const AlphaQuery q{scene_, ray, i};
      return meshes_[p.mesh]->occluded(local, q.filter());
    }
    if (p.kind == Primitive::Kind::kMesh) return meshes_[p.mesh]->occluded(local, block);
    Hit h;
    return scene_.intersectShape(i, ray, h);
  }

  bool occludedPrimitive(uint32_t i, const Ray& ray) const override {
    uint32_t block, member;
    if (!occludedPrimitive(i, ray, member, block)) return false;
    cacheOccluder(i, member, block);
    return true;
  }

  bool occludedBy(uint32_t item, uint32_t member, uint32_t block, const Ray& ray) const {
    const auto [i, first, count, boxes] = placed(item);
    const Primitive& p = scene_.primitives[i];
    Ray local;
    if (p.kind == Primitive::Kind::kMesh) {
      if (!meshes_[p.mesh] || alphaTested_[p.mesh] || member >= count) return false;
      // A group's blocker is the instance `member` of it; its box culls first (sub-pixel
      // instances rarely block a neighbouring shading point's shadow ray).
      if (boxes && !((hitGroupBoxes(boxes, kGroupBoxNodes, prepareBvh4Ray(ray.o, ray.d), ray.tmin,
                                    ray.tmax) >>
                      member) &
                     1))
        return false;
      return objectRay(p, first + member, ray, ray.tmax, local) &&
             meshes_[p.mesh]->occludedBy(local, block);
    }
    Hit h;
    return scene_.intersectShape(i, ray, h);
  }

  /// The any-hit test of textures/alpha.h for one mesh primitive, on the world-space ray (the hash
  /// of stochastic transparency reads it, as Embree's filter does).
  struct AlphaQuery {
    const Scene& scene;
    const Ray& worldRay;
    uint32_t primitive;
    static bool accept(const void* self, uint32_t triangle, float b1, float b2) {
      auto* q = static_cast<const AlphaQuery*>(self);
      return alphaAccepts(q->scene, q->worldRay, q->primitive, triangle, b1, b2);
    }
    TriangleFilter filter() const { return {&AlphaQuery::accept, this}; }
  };

  const Scene& scene_;
  std::vector<char> alphaTested_;  ///< by mesh index: its material is not OPAQUE
  TwoLevelOptions options_;
  uint64_t id_;
  std::vector<std::unique_ptr<MeshBvh>> meshes_;  ///< by mesh index; null when not placed
  TopLevel top_;  ///< accel/bvh_top_level.h
};

}  // namespace

int bvhBatchRays(BvhBatch batch) {
  switch (batch) {
    case BvhBatch::kLoop:
      return 1;
    case BvhBatch::kPacket8:
      return 8;
    case BvhBatch::kStream64:
      return 64;
  }
  return 1;
}

std::unique_ptr<Accelerator> makeTwoLevelAccelerator(const Scene& scene,
                                                     const TwoLevelOptions& options) {
  refuseEmbreeOnlyShapes(scene, "the in-house BVH (--accel bvh, bvh-gs, naive)");
  return std::make_unique<TwoLevelAccelerator>(scene, options);
}

std::unique_ptr<Accelerator> makeBvhAccelerator(const Scene& scene) {
  return makeTwoLevelAccelerator(scene, {});
}

std::unique_ptr<Accelerator> makeBvhGoldsmithSalmonAccelerator(const Scene& scene) {
  TwoLevelOptions o;
  o.build.builder = BvhBuilder::kGoldsmithSalmon;
  return makeTwoLevelAccelerator(scene, o);
}

BvhQuality bvhQuality(const Accelerator& accel) {
  auto* a = dynamic_cast<const TwoLevelAccelerator*>(&accel);
  return a ? a->quality() : BvhQuality{};
}

}  // namespace tray

#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/hit.h"
#include "core/ray.h"

namespace tray {

struct Scene;

/// Ray queries over a built scene. Implementations: Embree (accel/embree_accelerator.cpp) and
/// the in-house BVH. All must return the same hits for the same scene (tested).
class Accelerator {
 public:
  virtual ~Accelerator() = default;
  /// Closest hit with t in (ray.tmin, ray.tmax); false if none.
  virtual bool intersect(const Ray& ray, Hit& hit) const = 0;
  /// True if anything lies in (ray.tmin, ray.tmax): shadow rays.
  virtual bool occluded(const Ray& ray) const = 0;
  /// intersect() for each ray of a batch: found[i] = intersect(rays[i], hits[i]), the same
  /// hits. Wavefront integrators call it once per bounce with the whole queue. The default
  /// loops; an accelerator with a batched traversal (Embree's stream API) overrides it.
  virtual void intersectBatch(std::span<const Ray> rays, std::span<Hit> hits,
                              std::span<uint8_t> found) const {
    for (size_t i = 0; i < rays.size(); ++i) found[i] = intersect(rays[i], hits[i]);
  }
  /// intersectBatch() for rays known to be coherent (camera rays of a tile, in pixel order:
  /// neighbours start at one point in nearly one direction): the same hits, but an
  /// accelerator may trace them differently (Embree: RTC_INTERSECT_CONTEXT_FLAG_COHERENT).
  virtual void intersectCoherentBatch(std::span<const Ray> rays, std::span<Hit> hits,
                                      std::span<uint8_t> found) const {
    intersectBatch(rays, hits, found);
  }
  /// occluded() for each ray of a batch: blocked[i] = occluded(rays[i]).
  virtual void occludedBatch(std::span<const Ray> rays, std::span<uint8_t> blocked) const {
    for (size_t i = 0; i < rays.size(); ++i) blocked[i] = occluded(rays[i]);
  }
  /// Every hit in (ray.tmin, ray.tmax), sorted by t (ties by primitive then triangle). Used by
  /// CSG with mesh children, and by tests.
  virtual void allHits(const Ray& ray, std::vector<Hit>& hits) const = 0;
  /// Memory held by the acceleration structure, in bytes (for benchmarks; 0 if unknown).
  virtual size_t memoryBytes() const { return 0; }
};

/// Builds an accelerator over a scene that outlives it: how a layer below accel/ (a mesh used
/// as a CSG solid) gets one without depending on accel/ (accel/registry.h makes them by name).
using AcceleratorFactory = std::function<std::unique_ptr<Accelerator>(const Scene&)>;

}  // namespace tray

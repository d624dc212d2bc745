#pragma once
// Alpha-tested triangles in Embree: filter callbacks (the any-hit test of textures/alpha.h) on the
// triangle geometry of meshes whose material is not OPAQUE. Opaque meshes get no callback.
#include <embree3/rtcore.h>

#include "core/ray.h"
#include "core/scene.h"

namespace tray {

/// The intersect context of TRay's closest-hit and shadow queries: the filters read the scene
/// and the world-space ray from it (Embree hands them the ray in the instance's object space).
struct AlphaRayContext {
  RTCIntersectContext base;  ///< first: Embree sees a pointer to it
  const Scene* scene;
  const Ray* worldRay;   ///< the ray of a single-ray query
  const Ray* worldRays;  ///< a stream query's rays, indexed by each RTCRay's id
  AlphaRayContext(const Scene& s, const Ray& r) : scene(&s), worldRay(&r), worldRays(nullptr) {
    rtcInitIntersectContext(&base);
  }
  AlphaRayContext(const Scene& s, const Ray* rays)
      : scene(&s), worldRay(nullptr), worldRays(rays) {
    rtcInitIntersectContext(&base);
  }
};

/// Registers the intersect and occluded filters on triangle geometry `g` of `mesh` when its
/// material needs the alpha test. Queries must then pass an AlphaRayContext (all-hits queries,
/// which set a context filter, see every triangle).
void attachAlphaFilter(RTCGeometry g, const Scene& scene, const TriangleMesh& mesh);

}  // namespace tray

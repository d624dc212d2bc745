#pragma once
// How a ray enters a placed mesh in the two-level BVH: the same arithmetic for single rays
// (accel/bvh_accelerator.cpp) and packets (accel/bvh_batch.cpp), so both see the same hits.
#include "core/motion.h"
#include "core/ray.h"
#include "core/scene.h"

namespace tray {

/// The ray in p's object space (a moving p placed at the ray's time, as Embree's instance motion
/// places it), t unchanged (the direction is not normalised); false where p is flat at that time
/// (core/motion.h) and cannot be hit.
inline bool objectRay(const Primitive& p, const Ray& ray, float tmax, Ray& local) {
  Transform moved;
  const Transform* toWorld = placementAt(p, ray.time, moved);
  if (!toWorld) return false;
  local = Ray{toWorld->inversePoint(ray.o),
              toWorld->inverseVector(ray.d),
              ray.tmin,
              tmax,
              ray.blend,
              ray.time};  // the time places a deforming mesh's triangles
  return true;
}

/// The ray in instance `instance`'s object space of an instance array p (core/instance_array.h),
/// moved by its stored world-to-object matrix, t unchanged.
inline void arrayObjectRay(const Primitive& p, uint32_t instance, const Ray& ray, float tmax,
                           Ray& local) {
  const Affine3& w = p.instances->worldToObject[instance];
  local = Ray{affinePoint(w, ray.o), affineVector(w, ray.d), ray.tmin, tmax, ray.blend, ray.time};
}

/// objectRay for instance `instance` of p: an instance array's, else p's own placement.
inline bool objectRay(const Primitive& p, uint32_t instance, const Ray& ray, float tmax,
                      Ray& local) {
  if (p.instances) return arrayObjectRay(p, instance, ray, tmax, local), true;
  return objectRay(p, ray, tmax, local);
}

}  // namespace tray

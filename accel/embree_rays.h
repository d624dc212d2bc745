#pragma once
// Conversions between TRay's rays and hits and Embree 3's, shared by the single-ray and the
// batched queries.
#include <embree3/rtcore.h>

#include <cmath>
#include <limits>

#include "core/hit.h"
#include "core/ray.h"
#include "core/scene.h"

namespace tray {

/// Only the fields Embree reads (rtcIntersect1 docs): zero-filling the whole 80-byte RTCRayHit
/// for each of a path's rays costs more than it seems.
inline void toEmbree(const Ray& r, RTCRay& ray) {
  ray.org_x = r.o.x;
  ray.org_y = r.o.y;
  ray.org_z = r.o.z;
  ray.tnear = r.tmin;
  ray.dir_x = r.d.x;
  ray.dir_y = r.d.y;
  ray.dir_z = r.d.z;
  ray.time = r.time;
  ray.tfar = r.tmax;
  ray.mask = 0xffffffffu;
  ray.id = 0;
  ray.flags = 0;
}

/// Embree asserts RayK::valid() and aborts the whole process on a ray it cannot trace: an
/// origin or direction coordinate NaN or beyond FLT_LARGE (1.844e18), or a NaN t (issue 40).
/// render/ray_range.h refuses the scene values that would make one; these checks keep any that
/// is still made (a NaN from an extreme scene) from taking the process down.
inline bool embreeAccepts(const Ray& r) {
  constexpr float kLarge = 1.844e18f;  // Embree 3's FLT_LARGE
  // Every comparison made, then one test (& rather than &&): no branch per coordinate
  // (path_bench, Cornell box: the short-circuit form cost 1.3% of the wavefront's samples per
  // second). A NaN fails its comparison; t may be infinite, not NaN.
  return bool(int(std::fabs(r.o.x) <= kLarge) & int(std::fabs(r.o.y) <= kLarge) &
              int(std::fabs(r.o.z) <= kLarge) & int(std::fabs(r.d.x) <= kLarge) &
              int(std::fabs(r.d.y) <= kLarge) & int(std::fabs(r.d.z) <= kLarge) &
              int(r.tmin == r.tmin) & int(r.tmax == r.tmax));
}
/// A ray Embree accepts in place of one it would not: an empty interval, which meets nothing;
/// `blocked` (a shadow ray) gives it tfar = -inf, Embree's answer for an occluded ray, so that it
/// adds nothing either.
inline void emptyRay(RTCRay& ray, bool blocked) {
  ray.org_x = ray.org_y = ray.org_z = 0.0f;
  ray.dir_x = ray.dir_y = 0.0f, ray.dir_z = 1.0f;
  ray.tnear = blocked ? 0.0f : 1.0f;
  ray.tfar = blocked ? -std::numeric_limits<float>::infinity() : 0.0f;
}
/// toEmbree for a shadow query: a ray Embree would refuse comes back already occluded.
inline void toEmbreeShadow(const Ray& r, RTCRay& ray) {
  toEmbree(r, ray);
  if (!embreeAccepts(r)) [[unlikely]]
    emptyRay(ray, true);
}
inline RTCRayHit toEmbree(const Ray& r) {
  RTCRayHit rh;
  toEmbree(r, rh.ray);
  if (!embreeAccepts(r)) [[unlikely]]
    emptyRay(rh.ray, false);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

/// TRay's hit from Embree's: a mesh (an instance, or a mesh flattened into the top scene, whose
/// geometry id is its primitive's) or user geometry (an analytic shape).
inline Hit hitFromEmbree(const RTCHit& h, float t, const Scene& scene) {
  Hit hit;
  hit.t = t;
  const bool inTop = h.instID[0] == RTC_INVALID_GEOMETRY_ID;
  if (!inTop || scene.primitives[h.geomID].kind == Primitive::Kind::kMesh) {
    hit.primitive = inTop ? h.geomID : h.instID[0];
    hit.triangle = h.primID;
    hit.b1 = h.u;
    hit.b2 = h.v;
    // An instance array's hit carries its instance as geomID (accel/embree_instance_array.h);
    // any other instance's inner geometry id is 0.
    hit.instance = inTop ? 0 : h.geomID;
    // Embree's own curves and subdivision surfaces (accel/embree_native.h, instanced like
    // meshes) are shapes: their shade() reads Ng and u, v.
    if (!inTop && scene.primitives[hit.primitive].kind == Primitive::Kind::kShape) {
      hit.normal = {h.Ng_x, h.Ng_y, h.Ng_z};
      hit.uv = {h.u, h.v};
    }
  } else {
    // User geometry: primID carries the material override + 1 (0: none), Ng the object-space
    // normal and u, v the shape's uv (see accel/embree_shape_geometry.cpp, shapeIntersect).
    hit.primitive = h.geomID;
    hit.normal = {h.Ng_x, h.Ng_y, h.Ng_z};
    hit.uv = {h.u, h.v};
    hit.material = int(h.primID) - 1;
  }
  return hit;
}

}  // namespace tray

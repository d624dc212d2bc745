#pragma once
// Conversions between TRay's rays and hits and Embree 3's, shared by the single-ray and the
// batched queries.
#include <embree3/rtcore.h>

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
inline RTCRayHit toEmbree(const Ray& r) {
  RTCRayHit rh;
  toEmbree(r, rh.ray);
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
  } else {
    // User geometry: primID carries the material override + 1 (0: none), Ng the object-space
    // normal and u, v the shape's uv (see shapeIntersect).
    hit.primitive = h.geomID;
    hit.normal = {h.Ng_x, h.Ng_y, h.Ng_z};
    hit.uv = {h.u, h.v};
    hit.material = int(h.primID) - 1;
  }
  return hit;
}

}  // namespace tray

#include "accel/embree_instance_array.h"

#include <algorithm>

namespace tray {
namespace {

thread_local uint32_t tInstanceInFlight = 0;

/// Point and vector of the ray moved by instance k's world-to-object matrix (t unchanged: the
/// direction is not normalised, as Embree's own instances do).
template <class R>
void toObject(const Affine3& w, R& ray) {
  const float ox = ray.org_x, oy = ray.org_y, oz = ray.org_z;
  const float dx = ray.dir_x, dy = ray.dir_y, dz = ray.dir_z;
  ray.org_x = w.m[0][0] * ox + w.m[0][1] * oy + w.m[0][2] * oz + w.m[0][3];
  ray.org_y = w.m[1][0] * ox + w.m[1][1] * oy + w.m[1][2] * oz + w.m[1][3];
  ray.org_z = w.m[2][0] * ox + w.m[2][1] * oy + w.m[2][2] * oz + w.m[2][3];
  ray.dir_x = w.m[0][0] * dx + w.m[0][1] * dy + w.m[0][2] * dz;
  ray.dir_y = w.m[1][0] * dx + w.m[1][1] * dy + w.m[1][2] * dz;
  ray.dir_z = w.m[2][0] * dx + w.m[2][1] * dy + w.m[2][2] * dz;
}

void arrayBounds(const RTCBoundsFunctionArguments* args) {
  auto* d = static_cast<const EmbreeArrayData*>(args->geometryUserPtr);
  const Bounds3 b =
      groupBounds(&d->boxes[size_t(args->primID) * kEmbreeArrayBoxNodes], kEmbreeArrayBoxNodes);
  RTCBounds* o = args->bounds_o;
  o->lower_x = b.lo.x, o->lower_y = b.lo.y, o->lower_z = b.lo.z;
  o->upper_x = b.hi.x, o->upper_y = b.hi.y, o->upper_z = b.hi.z;
}

/// Bit k: the world-space ray enters the box of group g's instance k within [tnear, tfar].
template <class R>
unsigned enteredInstances(const EmbreeArrayData& d, unsigned g, const R& ray) {
  const uint32_t first = g * kEmbreeArrayGroup;
  prefetchGroupMatrices(*d.array, first,
                        std::min(kEmbreeArrayGroup, uint32_t(d.array->size()) - first));
  const float o[3] = {ray.org_x, ray.org_y, ray.org_z};
  const float inv[3] = {safeInverse(ray.dir_x), safeInverse(ray.dir_y), safeInverse(ray.dir_z)};
  return hitGroupBoxes(&d.boxes[size_t(g) * kEmbreeArrayBoxNodes], kEmbreeArrayBoxNodes,
                       bvh4Ray(o, inv), ray.tnear, ray.tfar);
}

// N is 1 on the single-ray queries TRay makes of scenes with user geometry
// (EmbreeAccelerator::streamable); a packet's lanes are taken one by one all the same.
void arrayIntersect(const RTCIntersectFunctionNArguments* args) {
  auto* d = static_cast<const EmbreeArrayData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const RTCRayHit world = rtcGetRayHitFromRayHitN(args->rayhit, args->N, i);
    float tfar = world.ray.tfar;  // lowered by each hit, so the group's next instance culls
    for (unsigned in = enteredInstances(*d, args->primID, world.ray); in; in &= in - 1) {
      const uint32_t instance = args->primID * kEmbreeArrayGroup + uint32_t(__builtin_ctz(in));
      RTCRayHit rh = world;
      rh.ray.tfar = tfar;
      toObject(d->array->worldToObject[instance], rh.ray);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      args->context->instID[0] = args->geomID;
      tInstanceInFlight = instance;
      rtcIntersect1(d->meshScene, args->context, &rh);
      args->context->instID[0] = RTC_INVALID_GEOMETRY_ID;
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
      tfar = rh.ray.tfar;
      RTCRayN_tfar(RTCRayHitN_RayN(args->rayhit, args->N), args->N, i) = rh.ray.tfar;
      RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
      RTCHitN_Ng_x(hit, args->N, i) = rh.hit.Ng_x;
      RTCHitN_Ng_y(hit, args->N, i) = rh.hit.Ng_y;
      RTCHitN_Ng_z(hit, args->N, i) = rh.hit.Ng_z;
      RTCHitN_u(hit, args->N, i) = rh.hit.u;
      RTCHitN_v(hit, args->N, i) = rh.hit.v;
      RTCHitN_primID(hit, args->N, i) = rh.hit.primID;
      RTCHitN_geomID(hit, args->N, i) = instance;  // the instance (see the header)
      RTCHitN_instID(hit, args->N, i, 0) = args->geomID;
    }
  }
}

void arrayOccluded(const RTCOccludedFunctionNArguments* args) {
  auto* d = static_cast<const EmbreeArrayData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const RTCRay world = rtcGetRayFromRayN(args->ray, args->N, i);
    for (unsigned in = enteredInstances(*d, args->primID, world); in; in &= in - 1) {
      const uint32_t instance = args->primID * kEmbreeArrayGroup + uint32_t(__builtin_ctz(in));
      RTCRay r = world;
      toObject(d->array->worldToObject[instance], r);
      args->context->instID[0] = args->geomID;
      tInstanceInFlight = instance;
      rtcOccluded1(d->meshScene, args->context, &r);
      args->context->instID[0] = RTC_INVALID_GEOMETRY_ID;
      if (r.tfar < 0) {
        RTCRayN_tfar(args->ray, args->N, i) = r.tfar;
        break;
      }
    }
  }
}

}  // namespace

RTCGeometry embreeInstanceArray(RTCDevice device, EmbreeArrayData& data) {
  const uint32_t groups =
      uint32_t((data.array->size() + kEmbreeArrayGroup - 1) / kEmbreeArrayGroup);
  data.boxes = instanceBoxes(*data.array, data.meshBounds, kEmbreeArrayGroup);
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, groups);
  rtcSetGeometryUserData(g, &data);
  rtcSetGeometryBoundsFunction(g, arrayBounds, nullptr);
  rtcSetGeometryIntersectFunction(g, arrayIntersect);
  rtcSetGeometryOccludedFunction(g, arrayOccluded);
  return g;
}

uint32_t embreeArrayInstanceInFlight() {
  return tInstanceInFlight;
}

}  // namespace tray

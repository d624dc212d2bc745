#include "accel/embree_instance_array.h"

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
  const Bounds3 b = d->array->placement(args->primID).bounds(d->meshBounds);
  RTCBounds* o = args->bounds_o;
  o->lower_x = b.lo.x, o->lower_y = b.lo.y, o->lower_z = b.lo.z;
  o->upper_x = b.hi.x, o->upper_y = b.hi.y, o->upper_z = b.hi.z;
}

// N is 1 on the single-ray queries TRay makes of scenes with user geometry
// (EmbreeAccelerator::streamable); a packet's lanes are taken one by one all the same.
void arrayIntersect(const RTCIntersectFunctionNArguments* args) {
  auto* d = static_cast<const EmbreeArrayData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    RTCRayHit rh = rtcGetRayHitFromRayHitN(args->rayhit, args->N, i);
    toObject(d->array->worldToObject[args->primID], rh.ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    args->context->instID[0] = args->geomID;
    tInstanceInFlight = args->primID;
    rtcIntersect1(d->meshScene, args->context, &rh);
    args->context->instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
    RTCRayN_tfar(RTCRayHitN_RayN(args->rayhit, args->N), args->N, i) = rh.ray.tfar;
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    RTCHitN_Ng_x(hit, args->N, i) = rh.hit.Ng_x;
    RTCHitN_Ng_y(hit, args->N, i) = rh.hit.Ng_y;
    RTCHitN_Ng_z(hit, args->N, i) = rh.hit.Ng_z;
    RTCHitN_u(hit, args->N, i) = rh.hit.u;
    RTCHitN_v(hit, args->N, i) = rh.hit.v;
    RTCHitN_primID(hit, args->N, i) = rh.hit.primID;
    RTCHitN_geomID(hit, args->N, i) = args->primID;  // the instance (see the header)
    RTCHitN_instID(hit, args->N, i, 0) = args->geomID;
  }
}

void arrayOccluded(const RTCOccludedFunctionNArguments* args) {
  auto* d = static_cast<const EmbreeArrayData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    RTCRay r = rtcGetRayFromRayN(args->ray, args->N, i);
    toObject(d->array->worldToObject[args->primID], r);
    args->context->instID[0] = args->geomID;
    tInstanceInFlight = args->primID;
    rtcOccluded1(d->meshScene, args->context, &r);
    args->context->instID[0] = RTC_INVALID_GEOMETRY_ID;
    if (r.tfar < 0) RTCRayN_tfar(args->ray, args->N, i) = r.tfar;
  }
}

}  // namespace

RTCGeometry embreeInstanceArray(RTCDevice device, const EmbreeArrayData& data) {
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, unsigned(data.array->size()));
  rtcSetGeometryUserData(g, const_cast<EmbreeArrayData*>(&data));
  rtcSetGeometryBoundsFunction(g, arrayBounds, nullptr);
  rtcSetGeometryIntersectFunction(g, arrayIntersect);
  rtcSetGeometryOccludedFunction(g, arrayOccluded);
  return g;
}

uint32_t embreeArrayInstanceInFlight() {
  return tInstanceInFlight;
}

}  // namespace tray

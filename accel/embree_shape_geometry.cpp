// Analytic shapes (spheres, boxes, CSG, planes) as Embree user geometry: one user primitive
// per shape primitive, whose callbacks call Scene::intersectShape on the world-space ray.
#include "accel/embree_shape_geometry.h"

#include <vector>

#include "accel/shape_crossings.h"
#include "core/motion.h"

namespace tray {
namespace {

// Embree rejects primitives whose bounds exceed ~1.8e18; infinite shapes (planes) are clamped
// to this extent, far beyond any scene that single-precision hit points can resolve.
constexpr float kMaxExtent = 1e17f;

void reportShapeHit(const RTCIntersectFunctionNArguments* args, const Hit& hit, uint32_t geomID) {
  RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  RTCHit candidate{};
  candidate.Ng_x = hit.normal.x;
  candidate.Ng_y = hit.normal.y;
  candidate.Ng_z = hit.normal.z;
  candidate.u = hit.uv.x;
  candidate.v = hit.uv.y;
  candidate.primID = uint32_t(hit.material + 1);
  candidate.geomID = geomID;
  candidate.instID[0] = RTC_INVALID_GEOMETRY_ID;
  float oldTfar = rh->ray.tfar;
  rh->ray.tfar = hit.t;
  int valid = -1;
  if (args->context->filter) {
    // Filters are not invoked for user geometry automatically (RenderKit/embree#478).
    RTCFilterFunctionNArguments fargs{&valid,
                                      args->geometryUserPtr,
                                      args->context,
                                      reinterpret_cast<RTCRayN*>(&rh->ray),
                                      reinterpret_cast<RTCHitN*>(&candidate),
                                      1};
    rtcFilterIntersection(args, &fargs);
  }
  if (valid != 0) {
    rh->hit = candidate;
  } else {
    rh->ray.tfar = oldTfar;
  }
}

void shapeBounds(const RTCBoundsFunctionArguments* args) {
  auto* data = static_cast<const ShapeUserData*>(args->geometryUserPtr);
  const Primitive& p = data->scene->primitives[data->primitive];
  // A moving shape: its box at this time step; Embree interpolates the boxes between steps.
  Transform step = p.toWorld;
  if (!p.motion.empty()) step.m = p.motion[args->timeStep];  // bounds() reads m only
  Bounds3 b = step.bounds(p.shape->bounds());
  b.lo = max(b.lo, Vec3(-kMaxExtent));
  b.hi = min(b.hi, Vec3(kMaxExtent));
  RTCBounds* o = args->bounds_o;
  o->lower_x = b.lo.x, o->lower_y = b.lo.y, o->lower_z = b.lo.z;
  o->upper_x = b.hi.x, o->upper_y = b.hi.y, o->upper_z = b.hi.z;
}

void shapeIntersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* data = static_cast<const ShapeUserData*>(args->geometryUserPtr);
  RTCRayHit* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  Ray ray{{rh->ray.org_x, rh->ray.org_y, rh->ray.org_z},
          {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z},
          rh->ray.tnear,
          rh->ray.tfar,
          BlendRays::kStochastic,
          rh->ray.time};
  if (args->context->filter) {
    // All-hits query: report every boundary crossing of the solid within the range.
    forEachShapeCrossing(data->scene->primitives[data->primitive], ray,
                         [&](const Hit& h) { reportShapeHit(args, h, args->geomID); });
    return;
  }
  Hit hit;
  if (data->scene->intersectShape(data->primitive, ray, hit))
    reportShapeHit(args, hit, args->geomID);
}

void shapeOccluded(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* data = static_cast<const ShapeUserData*>(args->geometryUserPtr);
  RTCRay* r = reinterpret_cast<RTCRay*>(args->ray);
  Ray ray{{r->org_x, r->org_y, r->org_z},
          {r->dir_x, r->dir_y, r->dir_z},
          r->tnear,
          r->tfar,
          BlendRays::kStochastic,
          r->time};
  Hit hit;
  if (data->scene->intersectShape(data->primitive, ray, hit)) r->tfar = -kInfinity;
}

}  // namespace

RTCGeometry embreeShapeGeometry(RTCDevice device, ShapeUserData& data) {
  const Primitive& p = data.scene->primitives[data.primitive];
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(g, 1);
  rtcSetGeometryUserData(g, &data);
  rtcSetGeometryBoundsFunction(g, shapeBounds, nullptr);
  rtcSetGeometryIntersectFunction(g, shapeIntersect);
  rtcSetGeometryOccludedFunction(g, shapeOccluded);
  // A moving shape: Embree asks shapeBounds for its box at each step.
  if (!p.motion.empty()) rtcSetGeometryTimeStepCount(g, unsigned(p.motion.size()));
  return g;
}

}  // namespace tray

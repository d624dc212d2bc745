#include "accel/embree_alpha_filter.h"

#include "textures/alpha.h"

namespace tray {

namespace {

void alphaFilter(const RTCFilterFunctionNArguments* args) {
  // All-hits queries (CSG over meshes) install a context filter and a context of another type.
  if (args->context->filter) return;
  const auto* ctx = reinterpret_cast<const AlphaRayContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    // An instance's id, or for a mesh flattened into the top scene its geometry's.
    uint32_t primitive = RTCHitN_instID(args->hit, args->N, i, 0);
    if (primitive == RTC_INVALID_GEOMETRY_ID) primitive = RTCHitN_geomID(args->hit, args->N, i);
    const uint32_t triangle = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    const Ray& ray =
        ctx->worldRay ? *ctx->worldRay : ctx->worldRays[RTCRayN_id(args->ray, args->N, i)];
    if (!alphaAccepts(*ctx->scene, ray, primitive, triangle, u, v)) args->valid[i] = 0;
  }
}

}  // namespace

void attachAlphaFilter(RTCGeometry g, const Scene& scene, const TriangleMesh& mesh) {
  if (!needsAlphaTest(scene.material(mesh.material))) return;
  rtcSetGeometryIntersectFilterFunction(g, alphaFilter);
  rtcSetGeometryOccludedFilterFunction(g, alphaFilter);
}

}  // namespace tray

// A mesh triangle's surface point, written once over the lane type (core/lane_ops.h,
// docs/lanes.md): the barycentric position, normals and uvs, placed in the world, with the
// shading normal's fallback and the geometric normal's side. Scene::surface (core/scene.cpp)
// calls it with float; the SIMD kernel integrators/surface_batch.cpp includes this file again
// in each target's pass with TRAY_LANES_SIMD defined, and gathers the corners it reads.
#ifdef TRAY_LANES_SIMD
#if defined(TRAY_CORE_SURFACE_LANES_SIMD_) == defined(HWY_TARGET_TOGGLE)
#ifdef TRAY_CORE_SURFACE_LANES_SIMD_
#undef TRAY_CORE_SURFACE_LANES_SIMD_
#else
#define TRAY_CORE_SURFACE_LANES_SIMD_
#endif
#define TRAY_LANES_BODY
#endif
#elif !defined(TRAY_CORE_SURFACE_LANES_SCALAR_)
#define TRAY_CORE_SURFACE_LANES_SCALAR_
#define TRAY_LANES_BODY
#endif

#ifdef TRAY_LANES_BODY
#undef TRAY_LANES_BODY
#include "core/lane_ops.h"
#include "core/transform_lanes.h"

// After every include: opens the namespace of this mode (scalar or SIMD).
#include "core/lanes_begin.h"  // IWYU pragma: keep

/// World-space front-face normal (unnormalised) of the object-space triangle (p0, p1, p2)
/// placed by the transform whose inverse matrix is inv (core/front_face.h: the rule).
template <class V3>
TRAY_LANE V3 triangleFrontNormal(const float (&inv)[4][4], const V3& p0, const V3& p1,
                                 const V3& p2) {
  return transformNormal(inv, cross(p1 - p0, p2 - p0));
}

/// What meshSurfaceOf writes, for a lane type without a SurfacePoint (the SIMD kernel's).
template <class F>
struct MeshSurfaceOf {
  Vec3Of<F> p, ng, n, front;
  Vec2Of<F> uv;
};

/// The surface point at barycentrics (b1, b2) of the object-space triangle (p0, p1, p2) placed
/// by the transform (m, its inverse inv): s.p, s.front (the winding's unit normal), s.n (the
/// interpolated shading normal, or the geometric one where the mesh has none or it does not
/// normalise) and s.ng (the geometric normal on the shading normal's side), s.uv (interpolated,
/// or (b1, b2) without uvs). normal(k) and uv(k) give corner k's (k = 0, 1, 2), read only where
/// hasNormals / hasUvs. S: SurfacePoint for float, MeshSurfaceOf for vectors.
template <class V3, class F, class Normals, class Uvs, class S>
TRAY_LANE void meshSurfaceOf(const float (&m)[4][4], const float (&inv)[4][4], F b1, F b2,
                             const V3& p0, const V3& p1, const V3& p2, bool hasNormals,
                             const Normals& normal, bool hasUvs, const Uvs& uv, S& s) {
  const F b0 = F(1.0f) - b1 - b2;
  s.p = transformPoint(m, b0 * p0 + b1 * p1 + b2 * p2);
  const V3 ng = normalize(triangleFrontNormal(inv, p0, p1, p2));
  s.front = ng;
  if (hasNormals) {
    const V3 nw = transformNormal(inv, b0 * normal(0) + b1 * normal(1) + b2 * normal(2));
    const F len = length(nw);
    const V3 n = select(len > F(0.0f) && isFiniteOf(len), nw / len, ng);
    s.n = n;
    // Shading keeps the geometric normal on the shading normal's side (flat fallback
    // otherwise); the front face for emission stays the winding's (s.front).
    s.ng = select(dot(n, ng) < F(0.0f), -ng, ng);
  } else {
    s.n = ng;
    s.ng = ng;
  }
  if (hasUvs) {
    const auto uv0 = uv(0), uv1 = uv(1), uv2 = uv(2);
    s.uv = {b0 * uv0.x + b1 * uv1.x + b2 * uv2.x, b0 * uv0.y + b1 * uv1.y + b2 * uv2.y};
  } else {
    s.uv = {b1, b2};
  }
}

#include "core/lanes_end.h"
#endif  // TRAY_LANES_BODY

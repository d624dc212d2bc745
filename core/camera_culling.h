#pragma once
// glTF 2.0 §3.9.4 ("Double Sided"): a material with doubleSided false is seen from its front
// face only; "back-face culling must be enabled". TRay culls for camera rays only: what the
// camera looks at through a single-sided surface's back (a helper box around a camera, a plane
// seen from behind, the inside of an open shell) is what lies beyond it, as in viewers.
// Secondary rays and shadow rays see both faces: light does not leak through single-sided
// walls, and a closed mesh stays closed for refraction and occlusion (docs/scene-format.md,
// "doubleSided").
#include "core/accelerator.h"
#include "core/front_face.h"
#include "core/scene.h"

namespace tray {

/// Camera rays pass at most this many culled faces (then the next face is a hit, culled or
/// not), so that a pathological stack of back faces cannot make one pixel unbounded work.
constexpr int kMaxCulledFaces = 64;

/// Whether a camera ray's hit is the back face of a single-sided triangle mesh.
inline bool cameraCulls(const Scene& scene, const Ray& ray, const Hit& hit) {
  if (hit.material >= 0) return false;  // CSG: solids have no back faces to cull
  const Primitive& p = scene.primitives[hit.primitive];
  if (p.kind != Primitive::Kind::kMesh) return false;
  const TriangleMesh& m = scene.meshes[p.mesh];
  if (scene.material(m.material).doubleSided) return false;
  const uint32_t* v = &m.indices[3 * size_t(hit.triangle)];
  Transform scratch;  // an instance array's instance (Scene::placement)
  const Transform& toWorld =
      p.instances ? scene.placement(hit.primitive, hit.instance, scratch) : p.toWorld;
  const Vec3 front =
      triangleFrontNormal(toWorld, m.positions[v[0]], m.positions[v[1]], m.positions[v[2]]);
  return dot(front, ray.d) > 0;
}

/// Given the camera ray's first hit, the first that is not culled: `hit` stays on the ray as
/// given (t from its origin). Returns false when the ray escapes past the culled faces. Callers
/// that already traced the ray (a batch) pass its hit instead of tracing it again.
inline bool passCulledFaces(const Accelerator& accel, const Scene& scene, const Ray& ray,
                            Hit& hit) {
  Ray beyond = ray;
  for (int culled = 0; culled < kMaxCulledFaces && cameraCulls(scene, ray, hit); ++culled) {
    // Just past the culled face, relative to its distance (a coplanar face is taken with it).
    beyond.tmin = std::max(hit.t * (1.0f + 1e-5f), hit.t + 1e-6f);
    hit = Hit{};
    if (!accel.intersect(beyond, hit)) return false;
  }
  return true;
}

/// The camera ray's first hit that is not culled; false when it escapes.
inline bool intersectCameraRay(const Accelerator& accel, const Scene& scene, const Ray& ray,
                               Hit& hit) {
  return accel.intersect(ray, hit) && passCulledFaces(accel, scene, ray, hit);
}

}  // namespace tray

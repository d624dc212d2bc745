#pragma once
#include <cstdint>

#include "core/math.h"

namespace tray {

constexpr uint32_t kNoPrimitive = 0xffffffffu;

/// What an accelerator reports: the cheap first phase of an intersection. The full surface
/// (normals, uv, material) is computed only for the closest hit by Scene::surface().
struct Hit {
  float t = kInfinity;
  uint32_t primitive = kNoPrimitive;  ///< index into Scene::primitives
  uint32_t triangle = 0;              ///< triangle index within the mesh (meshes only)
  float b1 = 0, b2 = 0;               ///< barycentrics of vertices 1 and 2 (meshes only)
  Vec3 normal;                        ///< object-space geometric normal (analytic shapes only)
  Vec2 uv;                            ///< surface parameterisation (analytic shapes only)
  int material = -1;                  ///< overrides the primitive's material when >= 0 (CSG)
  uint32_t instance = 0;              ///< instance arrays: the instance hit (core/instance_array.h)
  bool valid() const { return primitive != kNoPrimitive; }
};

/// The second phase: everything shading needs, in world space.
struct SurfacePoint {
  Vec3 p;                   ///< hit position (refined onto the surface)
  Vec3 ng;                  ///< unit geometric normal, on the outward side of the surface
  Vec3 n;                   ///< unit shading normal (interpolated for smooth meshes)
  Vec2 uv;                  ///< texture coordinates
  int material = 0;         ///< index into Scene::materials
  uint32_t primitive = kNoPrimitive;
  uint32_t instance = 0;    ///< instance arrays: the instance (Hit::instance); else 0
  Vec3 front;               ///< unit front-face normal (core/front_face.h: the winding, not
                            ///< vertex normals): the side one-sided emitters emit from
  bool frontFace = true;    ///< the ray arrived from the side ng points to
  float time = 0.0f;        ///< the ray's shutter time (Ray::time): rays leaving here keep it
  Vec3 tangent;             ///< curves (shapes/curves.h): unit direction along the fibre; else 0
};

}  // namespace tray

#pragma once
// The texture-space frame of a surface point: what texture filtering and normal mapping need
// beyond SurfacePoint, computed only for materials with textures.
#include "core/hit.h"
#include "core/scene.h"

namespace tray {

struct UvFrame {
  Vec2 uv;          ///< in the requested uv set
  Vec3 dpdu, dpdv;  ///< world-space change of the point per unit u and v; zero if degenerate
  Vec3 tangent;     ///< world-space vertex tangent (meshes with tangents), else zero
  float bitangentSign = 1.0f;  ///< glTF TANGENT.w: bitangent = sign * cross(n, tangent)
};

/// The frame of uv set `set` (TEXCOORD_n) at the surface `s` of `hit`. A mesh without that set
/// falls back to TEXCOORD_0 (then to the barycentrics SurfacePoint uses); dp/du and dp/dv are
/// per triangle (pbrt-v4 §6.5.3), or the analytic shape's own.
UvFrame surfaceUvFrame(const Scene& scene, const Hit& hit, const SurfacePoint& s, int set);

}  // namespace tray

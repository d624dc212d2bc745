#pragma once
// The tangent frame of a surface point that normal maps (glTF 2.0 §3.9.3) and
// KHR_materials_anisotropy's direction are expressed in.
#include <cmath>

#include "core/sampling.h"
#include "textures/surface_uv.h"

namespace tray {

/// Unit t and b = sign cross(n, t) around unit n: t is the vertex tangent (glTF TANGENT, or
/// shapes/mesh_tangents.h's MikkTSpace-like one) or else the triangle's dp/du, projected onto
/// the plane of n; sign is TANGENT.w, or for dp/du the side dp/dv lies on. Any perpendicular
/// pair where t has no length there.
inline void tangentFrame(const Vec3& n, const UvFrame& f, Vec3& t, Vec3& b) {
  t = isBlack(f.tangent) ? f.dpdu : f.tangent;
  float sign = f.bitangentSign;
  if (isBlack(f.tangent)) sign = dot(cross(n, f.dpdu), f.dpdv) < 0 ? 1.0f : -1.0f;
  t = t - n * dot(n, t);
  float len = length(t);
  if (len > 0 && std::isfinite(len)) {
    t = t / len;
    b = sign * cross(n, t);
  } else {
    orthonormalBasis(n, t, b);
  }
}

/// KHR_materials_anisotropy's direction in world space (README, "Anisotropy"): the texture's
/// RG (2 rg - 1, in tangent space; (1, 0) without a texture) rotated by `rotation` radians
/// counter-clockwise about n, placed in the frame (t, b). The texture's B scales the strength
/// (the caller's).
inline Vec3 anisotropyDirection(const Vec3& n, const UvFrame& f, float rotation, Vec2 texelRg,
                                bool textured) {
  Vec3 t, b;
  tangentFrame(n, f, t, b);
  Vec2 d{1.0f, 0.0f};
  if (textured) {
    d = {2.0f * texelRg.x - 1.0f, 2.0f * texelRg.y - 1.0f};
    const float len = std::sqrt(d.x * d.x + d.y * d.y);
    d = len > 0 ? Vec2{d.x / len, d.y / len} : Vec2{1.0f, 0.0f};
  }
  const float c = std::cos(rotation), s = std::sin(rotation);
  const Vec2 r{c * d.x - s * d.y, s * d.x + c * d.y};
  return r.x * t + r.y * b;
}

}  // namespace tray

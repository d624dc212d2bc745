#pragma once
// The one front-face rule for one-sided emitters, shared by Scene::surface (what BSDF
// sampling sees when it hits an emitter) and the area lights (what light sampling samples),
// so that both strategies of MIS integrate the same emission.
#include "core/surface_lanes.h"
#include "core/transform.h"

namespace tray {

/// World-space front-face normal (unnormalised) of the object-space triangle (p0, p1, p2)
/// placed by toWorld. glTF 2.0 3.7.2.1: the front face is the counter-clockwise one; vertex
/// normals do not define facing. The winding normal goes through the inverse transpose, so a
/// mirroring node transform (negative determinant) flips the front face, as glTF prescribes.
/// The formula is core/surface_lanes.h's, which the SIMD surface kernel shares.
inline Vec3 triangleFrontNormal(const Transform& toWorld, const Vec3& p0, const Vec3& p1,
                                const Vec3& p2) {
  return triangleFrontNormal(toWorld.inv.m, p0, p1, p2);
}

/// Whether a surface with front-face normal `front` (analytic shapes: the outward normal)
/// emits along w, the direction leaving the surface (any length). glTF's doubleSided
/// materials emit from both faces.
inline bool emitsToward(const Vec3& front, const Vec3& w, bool doubleSided) {
  return doubleSided || dot(front, w) > 0;
}

}  // namespace tray

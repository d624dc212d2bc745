#pragma once
// Motion blur of placed primitives (docs/scene-format.md, "Motion blur"): a moving primitive
// carries its object-to-world matrix at N steps evenly spaced over the shutter
// (Primitive::motion), and a ray at shutter time t in [0, 1] sees it at the linear
// interpolation between the two steps around t, matrix entry by entry, as Embree interpolates
// an instance given one matrix per time step (rtcSetGeometryTimeStepCount and
// rtcSetGeometryTransform; its quaternion form, which slerps rotations, is not used). A
// deforming mesh's vertices move the same way (one vertex buffer per time step).
#include "core/scene.h"

namespace tray {

/// Embree's time segments: of `count` >= 2 steps evenly spaced over [0, 1], the segment that
/// holds t (clamped to [0, 1]) and the fraction of the way through it.
void timeSegment(size_t count, float t, size_t& segment, float& fraction);

/// Vertex v of a deforming mesh (positionSteps not empty) at shutter time t: the linear
/// interpolation of its positionSteps.
Vec3 deformedVertexAt(const TriangleMesh& mesh, uint32_t v, float t);

/// Vertex v of `mesh` at shutter time t: its position, or for a deforming mesh the linear
/// interpolation of its positionSteps. Inline: the static case is one load, where the call
/// cost Scene::surface 45 instructions per hit (callgrind, Cornell box).
inline Vec3 vertexAt(const TriangleMesh& mesh, uint32_t v, float t) {
  if (mesh.positionSteps.empty()) return mesh.positions[v];
  return deformedVertexAt(mesh, v, t);
}

/// The matrix of `steps` (N >= 1, evenly spaced over time 0 to 1) at time t, clamped to [0, 1]:
/// the segment floor(t (N - 1)) and the fraction within it, as Embree's time segments.
Mat4 interpolateSteps(const std::vector<Mat4>& steps, float t);

/// placementAt for a moving primitive (motion not empty).
const Transform* movedPlacementAt(const Primitive& p, float t, Transform& moved);

/// p's object-to-world transform at shutter time t: &p.toWorld when p is static (no copy), else
/// `moved`, filled with the interpolated placement. Null where that matrix is singular (between
/// two steps a half turn passes through zero scale): the object is flat at that instant and
/// rays miss it; `moved.m` then holds the matrix.
inline const Transform* placementAt(const Primitive& p, float t, Transform& moved) {
  if (p.motion.empty()) return &p.toWorld;
  return movedPlacementAt(p, t, moved);
}

/// World bounds of p's object-space `local` box over the whole shutter: the union of its boxes
/// at every step, which holds every interpolated placement (a point's world position moves
/// linearly between two steps, so it stays in the box of its two end positions).
Bounds3 motionBounds(const Primitive& p, const Bounds3& local);

/// True when `steps` are not all equal: a primitive with such steps moves.
bool stepsMove(const std::vector<Mat4>& steps);

}  // namespace tray

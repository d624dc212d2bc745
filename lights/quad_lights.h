#pragma once
// Rectangles in emissive meshes: pairs of triangles that share an edge and together form a
// rectangle (a quad exported as two triangles: the Cornell box's light, panels, lamps), so
// that LightSet can sample each as one rectangle by solid angle (Urena et al. 2013,
// lights/rectangle_light_lanes.h) instead of two triangles.
#include <cstdint>
#include <vector>

#include "core/transform.h"
#include "core/triangle_mesh.h"

namespace tray {

/// Two triangles of a mesh that form the rectangle corner + s ex + t ey (s, t in [0, 1],
/// world space, ex and ey perpendicular); `first` < `second` are their indices in the mesh.
struct MeshRectangle {
  uint32_t first, second;
  Vec3 corner, ex, ey;
};

/// The rectangles of `mesh` placed by toWorld, in the order of their first triangles: each
/// triangle pairs with the first unpaired triangle before it that shares an edge (vertices at
/// equal object-space positions) when the shared edge is the diagonal of a rectangle within
/// `tolerance`: the opposite corners c, d satisfy |c + d - a - b| <= tolerance |a - b|
/// (a parallelogram), |(a - c).(b - c)| <= tolerance |a - c| |b - c| (a right angle), and
/// both triangles' front normals point the same way. A parallelogram that is no rectangle,
/// or a kite, stays two triangles. World space: a shearing transform can unmake a rectangle.
std::vector<MeshRectangle> findMeshRectangles(const TriangleMesh& mesh, const Transform& toWorld,
                                              float tolerance = 1e-4f);

}  // namespace tray

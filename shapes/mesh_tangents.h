#pragma once
// Per-vertex tangents for normal mapping when a glTF mesh has no TANGENT attribute.
#include "core/triangle_mesh.h"

namespace tray {

/// Fills mesh.tangents / tangentSigns from the uv set `set` (0 or 1) and the vertex normals,
/// the way MikkTSpace (Mikkelsen 2008, the tangent space glTF 2.0 §3.7.2.1 names) does in its
/// common case: each triangle's dp/du, projected into the vertex's tangent plane, normalised and
/// weighted by the triangle's angle at the vertex; the sign says whether the bitangent
/// cross(n, t) points along -dp/dv (glTF's image "up", v = 0 at the top) or is mirrored.
/// Unlike MikkTSpace, vertices are never split where neighbouring triangles' tangent frames
/// disagree (mirrored uv seams): such a vertex keeps the majority's sign. No-op without
/// normals or that uv set.
void computeTangents(TriangleMesh& mesh, int set = 0);

}  // namespace tray

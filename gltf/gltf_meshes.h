#pragma once
// glTF mesh primitives (glTF 2.0 §3.7.2) into tray::TriangleMesh, one per triangle primitive.
#include <functional>
#include <vector>

#include "core/triangle_mesh.h"
#include "gltf/gltf_context.h"

namespace tray {

/// Running totals over a file's meshes: caps are checked against them before allocating, and
/// the loader turns the counts into one warning line each.
struct MeshStats {
  size_t triangles = 0, vertices = 0;
  size_t pointAndLinePrimitives = 0;     ///< skipped: TRay renders surfaces only
  size_t primitivesWithoutPosition = 0;  ///< skipped, as glTF 2.0 §3.7.2.1 advises
  size_t degenerateTriangles = 0;        ///< dropped: zero area or repeated vertex
  size_t repairedAttributes = 0;         ///< non-finite normals, tangents or uvs set to zero
};

/// Called per primitive with its vertices as read, before triangles are built: morph targets and
/// skinning (gltf/gltf_deform.h) change positions, normals and tangents here.
using VertexHook = std::function<void(size_t primitive, TriangleMesh& mesh)>;

/// Converts glTF mesh `index`: triangle lists, strips and fans become indexed triangle lists;
/// POSITION, NORMAL, TANGENT, TEXCOORD_0/1 and COLOR_0 are read. Fails on out-of-range indices and
/// on NaN or infinite positions. A primitive without material gets `defaultMaterial`.
std::vector<TriangleMesh> convertMesh(const GltfContext& ctx, int index, int defaultMaterial,
                                      MeshStats& stats, const VertexHook& deform = {});

}  // namespace tray

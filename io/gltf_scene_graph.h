#pragma once
// The node hierarchy (glTF 2.0 §3.5): world transforms composed down the tree, and what each
// node places into the scene: mesh instances, TRAY_shape shapes, cameras, lights.
#include <vector>

#include "core/scene.h"
#include "io/gltf_context.h"

namespace tray {

/// Meshes converted from every glTF mesh, moved into the Scene on first use so a mesh used by
/// several nodes is stored once and instanced.
struct MeshTable {
  std::vector<std::vector<TriangleMesh>> converted;  ///< per glTF mesh
  std::vector<std::vector<uint32_t>> placed;         ///< per glTF mesh: Scene::meshes indices
  std::vector<bool> moved;
};

/// Local transform of node `index` from `matrix` or TRS, checked finite (glTF 2.0 §3.5.2).
Mat4 localMatrix(const GltfContext& ctx, int index);

/// Checks every node's transform, TRAY_shape and light reference and every scene's
/// TRAY_environment, so a broken node fails the file even when no scene uses it.
void checkAllNodes(const GltfContext& ctx);

/// Walks glTF scene `sceneIndex` depth first (iteratively: no recursion depth to exhaust) and
/// appends primitives, cameras (in traversal order) and lights to `scene`, and sets its
/// environment. Shapes and meshes without material get `defaultMaterial`.
void addSceneNodes(const GltfContext& ctx, int sceneIndex, int defaultMaterial, MeshTable& meshes,
                   Scene& scene);

}  // namespace tray

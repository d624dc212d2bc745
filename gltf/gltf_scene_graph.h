#pragma once
// The node hierarchy (glTF 2.0 §3.5): world transforms composed down the tree, and what each
// node places into the scene: mesh instances, TRAY_shape shapes, cameras, lights.
#include <optional>
#include <vector>

#include "core/scene.h"
#include "gltf/gltf_context.h"
#include "gltf/gltf_deform.h"
#include "gltf/gltf_instancing.h"
#include "gltf/gltf_meshes.h"
#include "gltf/tray_shape.h"

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

/// Every camera, light, node and scene environment of the document, each converted once (and
/// so checked, used or not: a broken node fails the file even when no scene uses it). The walk
/// of the chosen scene only places these.
struct ObjectTable {
  std::vector<CameraDesc> cameras;               ///< per glTF camera
  std::vector<PunctualLightDesc> lights;         ///< per glTF light (KHR_lights_punctual)
  std::vector<Mat4> localMatrices;               ///< per node: matrix or TRS (glTF 2.0 §3.5.2)
  std::vector<int> nodeLights;                   ///< per node: its light, or -1
  std::vector<std::optional<TrayShape>> shapes;  ///< per node: its TRAY_shape, if any
  std::vector<Environment> environments;         ///< per scene: its TRAY_environment
  /// Per node: its EXT_mesh_gpu_instancing attributes, if any (gltf/gltf_instancing.h).
  std::vector<std::optional<InstanceAttributes>> instancing;
};

/// Converts every object of the document once; throws (ctx.fail) on the first invalid one.
ObjectTable convertObjects(const GltfContext& ctx);

/// Walks glTF scene `sceneIndex` depth first (iteratively: no recursion depth to exhaust) and
/// appends primitives, cameras (in traversal order) and lights to `scene`, and sets its
/// environment. Shapes and meshes without material get `defaultMaterial`. A node whose mesh
/// `deformer` deforms (skin, non-zero morph weights) gets geometry of its own, converted again
/// through the deformer; `stats` counts it against the vertex and triangle caps. With
/// `stepDeformers` (motion blur: one per motion step), such a mesh whose vertices differ between
/// the steps gets their positions at each (TriangleMesh::positionSteps). A node with
/// EXT_mesh_gpu_instancing places one primitive per instance (and mesh primitive) at its world
/// matrix times the instance's, object id nodes.size() + (instances placed before it), named
/// "<node>#k"; `instanceNodes`, if given, gets per primitive its node for instances, -1 for
/// the others (whose objectId is their node).
void addSceneNodes(const GltfContext& ctx, const ObjectTable& objects, int sceneIndex,
                   int defaultMaterial, MeshTable& meshes, const Deformer& deformer,
                   MeshStats& stats, Scene& scene,
                   const std::vector<Deformer>* stepDeformers = nullptr,
                   std::vector<int>* instanceNodes = nullptr,
                   size_t instanceArrayMin = kInstanceArrayMinInstances);  // 0: never

}  // namespace tray

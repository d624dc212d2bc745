#pragma once
// Motion blur from glTF animations (docs/scene-format.md, "Motion blur"): the nodes posed at
// several times over the shutter, and every placed primitive whose world transform changes over
// them made a moving one (core/motion.h).
#include <vector>

#include "core/scene.h"
#include "gltf/gltf_animation.h"
#include "gltf/gltf_context.h"
#include "gltf/gltf_deform.h"

namespace tray {

struct MotionSteps {
  float open = 0, close = 0;  ///< the shutter, in seconds
  int count = 0;              ///< times posed, evenly spaced from open to close; 0: none
  /// The times of the steps, in seconds (the last exactly `close`).
  std::vector<float> times() const;
};

/// The nodes posed by animation `which` at time t: what the animations set per node, and every
/// node's world matrix (`local`: every node's local matrix as placed; unanimated ones kept).
struct PosedNodes {
  std::vector<NodePose> poses;
  std::vector<Mat4> world;
};
PosedNodes poseNodes(const GltfContext& ctx, const std::vector<Animation>& animations, int which,
                     std::vector<Mat4> local, float t);

/// Places what moves over `steps`: `world` holds every node's world matrix at each of the
/// steps' times (poseNodes' `world`, per step). A primitive whose node's world matrix is not
/// the same at every step gets those matrices as Primitive::motion; one that stays put over
/// the shutter stays static. Skinned meshes are placed by their joints alone:
/// their motion is their vertices' (TriangleMesh::positionSteps, set by addSceneNodes). An
/// animated camera node gets its steps as CameraDesc::motion. Sets scene.shutterOpen and
/// shutterClose.
/// EXT_mesh_gpu_instancing instances (instanceNodes[i] >= 0: primitive i is an instance of that
/// node; empty: none) move with their node: node world at the step * inverse of the node's world
/// at the frame (`frameWorld`, per node) * the instance's frame placement.
void addMotionSteps(const GltfContext& ctx, const std::vector<std::vector<Mat4>>& world,
                    const Deformer& deformer, const MotionSteps& steps, Scene& scene,
                    const std::vector<int>& instanceNodes = {},
                    const std::vector<Mat4>& frameWorld = {});

/// Motion vectors: poses animation `which` at `time` (the previous frame) and records every
/// primitive's placement then (Scene::previousToWorld; skinned meshes: their frame placement,
/// no deformation) and every camera's (CameraDesc::previousToWorld, when it differs).
void addPreviousFrame(const GltfContext& ctx, const std::vector<Animation>& animations, int which,
                      const std::vector<Mat4>& local, const Deformer& deformer, float time,
                      Scene& scene, const std::vector<int>& instanceNodes = {},
                      const std::vector<Mat4>& frameWorld = {});

}  // namespace tray

#include "gltf/gltf_motion.h"

#include <algorithm>

#include "core/motion.h"

namespace tray {

std::vector<float> MotionSteps::times() const {
  std::vector<float> t;
  for (int k = 0; k < count; ++k) {
    const float u = float(k) / float(count - 1);
    // The last step lands on close exactly, whatever the rounding of open + u (close - open).
    t.push_back(k + 1 == count ? close : open + u * (close - open));
  }
  return t;
}

PosedNodes poseNodes(const GltfContext& ctx, const std::vector<Animation>& animations, int which,
                     std::vector<Mat4> local, float t) {
  PosedNodes posed;
  posed.poses = poseAt(ctx, animations, which, t);
  for (size_t i = 0; i < posed.poses.size(); ++i)
    if (posed.poses[i].animatesTransform()) local[i] = animatedMatrix(ctx, int(i), posed.poses[i]);
  posed.world = worldMatrices(ctx, local);
  return posed;
}

namespace {

/// Where primitive p (instance of node instanceNode, or -1) is when its node is at nodeWorld.
Mat4 placedAt(const Primitive& p, int instanceNode, const Mat4& nodeWorld,
              const std::vector<Mat4>& frameWorld) {
  if (instanceNode < 0) return nodeWorld;
  const Mat4& frame = frameWorld[size_t(instanceNode)];
  // Equal when the node does not move: the instance stays exactly where the frame put it.
  if (std::equal(&frame.m[0][0], &frame.m[0][0] + 16, &nodeWorld.m[0][0])) return p.toWorld.m;
  Mat4 inv;
  invert(frame, inv);  // invertible: the walk placed the instance only then
  return nodeWorld * (inv * p.toWorld.m);
}

}  // namespace

void addMotionSteps(const GltfContext& ctx, const std::vector<std::vector<Mat4>>& world,
                    const Deformer& deformer, const MotionSteps& steps, Scene& scene,
                    const std::vector<int>& instanceNodes, const std::vector<Mat4>& frameWorld) {
  if (steps.count < 2) return;
  scene.shutterOpen = steps.open, scene.shutterClose = steps.close;
  for (CameraDesc& c : scene.cameras) {  // an animated camera blurs the whole image
    if (c.node < 0) continue;
    std::vector<Mat4> motion;
    for (const auto& w : world) motion.push_back(w[size_t(c.node)]);
    if (!stepsMove(motion)) continue;
    for (const Mat4& m : motion)
      if (!m.isFinite())
        ctx.fail("node " + std::to_string(c.node) +
                 " (a camera) world transform overflows to infinity over the shutter");
    c.motion = std::move(motion);
  }
  for (size_t i = 0; i < scene.primitives.size(); ++i) {
    Primitive& p = scene.primitives[i];
    const int instanceNode = instanceNodes.empty() ? -1 : instanceNodes[i];
    const int node = instanceNode >= 0 ? instanceNode : p.objectId;
    // A skinned mesh is placed by its joints alone: its motion is in its positionSteps.
    if (deformer.skinned(node)) continue;
    std::vector<Mat4> motion;
    for (const auto& w : world)
      motion.push_back(placedAt(p, instanceNode, w[size_t(node)], frameWorld));
    if (stepsMove(motion)) {
      for (const Mat4& m : motion)
        if (!m.isFinite())
          ctx.fail("node " + std::to_string(node) +
                   " world transform overflows to infinity over the shutter");
      p.motion = std::move(motion);
    } else if (stepsMove({p.toWorld.m, motion[0]})) {
      // Static over a shutter that does not hold the frame: placed where the shutter sees it.
      Mat4 inv;
      if (motion[0].isFinite() && invert(motion[0], inv)) p.toWorld = Transform(motion[0]);
    }
  }
}

void addPreviousFrame(const GltfContext& ctx, const std::vector<Animation>& animations, int which,
                      const std::vector<Mat4>& local, const Deformer& deformer, float time,
                      Scene& scene, const std::vector<int>& instanceNodes,
                      const std::vector<Mat4>& frameWorld) {
  const std::vector<Mat4> world = poseNodes(ctx, animations, which, local, time).world;
  scene.previousToWorld.clear();
  for (size_t i = 0; i < scene.primitives.size(); ++i) {
    const Primitive& p = scene.primitives[i];
    const int instanceNode = instanceNodes.empty() ? -1 : instanceNodes[i];
    const int node = instanceNode >= 0 ? instanceNode : p.objectId;
    scene.previousToWorld.push_back(
        deformer.skinned(node) ? p.toWorld.m
                               : placedAt(p, instanceNode, world[size_t(node)], frameWorld));
  }
  for (CameraDesc& c : scene.cameras) {
    if (c.node < 0 || !stepsMove({c.toWorld.m, world[size_t(c.node)]})) continue;
    Mat4 inv;
    if (world[size_t(c.node)].isFinite() && invert(world[size_t(c.node)], inv))
      c.previousToWorld = Transform(world[size_t(c.node)]);
  }
}

}  // namespace tray

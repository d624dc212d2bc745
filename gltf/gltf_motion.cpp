#include "gltf/gltf_motion.h"

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

void addMotionSteps(const GltfContext& ctx, const std::vector<std::vector<Mat4>>& world,
                    const Deformer& deformer, const MotionSteps& steps, Scene& scene) {
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
  for (Primitive& p : scene.primitives) {
    const int node = p.objectId;
    // A skinned mesh is placed by its joints alone: its motion is in its positionSteps.
    if (deformer.skinned(node)) continue;
    std::vector<Mat4> motion;
    for (const auto& w : world) motion.push_back(w[size_t(node)]);
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
                      Scene& scene) {
  const std::vector<Mat4> world = poseNodes(ctx, animations, which, local, time).world;
  scene.previousToWorld.clear();
  for (const Primitive& p : scene.primitives)
    scene.previousToWorld.push_back(deformer.skinned(p.objectId) ? p.toWorld.m
                                                                 : world[size_t(p.objectId)]);
  for (CameraDesc& c : scene.cameras) {
    if (c.node < 0 || !stepsMove({c.toWorld.m, world[size_t(c.node)]})) continue;
    Mat4 inv;
    if (world[size_t(c.node)].isFinite() && invert(world[size_t(c.node)], inv))
      c.previousToWorld = Transform(world[size_t(c.node)]);
  }
}

}  // namespace tray

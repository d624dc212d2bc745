#include "io/gltf_motion.h"

#include "core/motion.h"

namespace tray {

namespace {

/// Every node's world matrix at time t: the animated nodes posed, the others as in `local`.
std::vector<Mat4> worldAt(const GltfContext& ctx, const std::vector<Animation>& animations,
                          int which, std::vector<Mat4> local, float t) {
  const std::vector<NodePose> poses = poseAt(ctx, animations, which, t);
  for (size_t i = 0; i < poses.size(); ++i)
    if (poses[i].animatesTransform()) local[i] = animatedMatrix(ctx, int(i), poses[i]);
  return worldMatrices(ctx, local);
}

}  // namespace

void addMotionSteps(const GltfContext& ctx, const std::vector<Animation>& animations, int which,
                    const std::vector<Mat4>& local, const Deformer& deformer,
                    const MotionSteps& steps, Scene& scene) {
  if (steps.count < 2) return;
  scene.shutterOpen = steps.open, scene.shutterClose = steps.close;
  std::vector<std::vector<Mat4>> world;  // per step, per node
  for (int k = 0; k < steps.count; ++k) {
    const float u = float(k) / float(steps.count - 1);
    // The last step lands on close exactly, whatever the rounding of open + u (close - open).
    const float t =
        k + 1 == steps.count ? steps.close : steps.open + u * (steps.close - steps.open);
    world.push_back(worldAt(ctx, animations, which, local, t));
  }
  for (Primitive& p : scene.primitives) {
    const int node = p.objectId;
    // A skinned mesh is placed by its joints, baked into its vertices at the frame's time.
    if (deformer.skinned(node)) continue;
    std::vector<Mat4> motion;
    for (const auto& w : world) motion.push_back(w[size_t(node)]);
    if (stepsMove(motion)) {
      for (const Mat4& m : motion)
        if (!m.isFinite()) ctx.fail("node " + std::to_string(node) +
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
  const std::vector<Mat4> world = worldAt(ctx, animations, which, local, time);
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

#pragma once
// glTF animations (glTF 2.0 §3.11): keyframe samplers and the channels that drive node
// translation, rotation, scale and morph weights, sampled at one time.
#include <optional>
#include <string>
#include <vector>

#include "core/transform.h"
#include "gltf/gltf_context.h"

namespace tray {

enum class Interpolation { kLinear, kStep, kCubicSpline };

/// One sampler's keyframes (glTF 2.0 §3.11, "Animation samplers").
struct Keyframes {
  std::vector<float> times;  ///< strictly increasing
  /// Per key `width` floats; CUBICSPLINE: in-tangent, value and out-tangent per key.
  std::vector<float> values;
  int width = 1;  ///< floats per value: 3 (T, S), 4 (R), morph target count (weights)
  Interpolation mode = Interpolation::kLinear;
  bool quaternion = false;  ///< rotations: slerp on the shortest path, renormalised
};

/// The value at time t, clamped to the first and last keyframe (glTF 2.0 Appendix C).
std::vector<float> sampleKeyframes(const Keyframes& k, float t);

enum class AnimatedPath { kTranslation, kRotation, kScale, kWeights };

struct AnimationChannel {
  int node = -1;
  AnimatedPath path = AnimatedPath::kTranslation;
  Keyframes keys;
};

struct Animation {
  std::string name;
  std::vector<AnimationChannel> channels;
};

/// Reads and checks every animation of the document: sampler and node references, accessor
/// types and counts, strictly increasing times. Throws (ctx.fail) on the first problem.
std::vector<Animation> readAnimations(const GltfContext& ctx);

/// Which animation `which` names: "all" (-1), an index or a name. Throws if there is none.
int chooseAnimation(const GltfContext& ctx, const std::vector<Animation>& animations,
                    const std::string& which);

/// What the animations set for one node at one time; absent parts keep the node's own values.
struct NodePose {
  std::optional<Vec3> translation, scale;
  std::optional<std::vector<float>> rotation;  ///< x y z w, unit length
  std::optional<std::vector<float>> weights;   ///< morph weights
  bool animatesTransform() const { return translation || rotation || scale; }
};

/// Poses of every node at time `t` from animation `which` (-1: all of them; a later channel
/// overrides an earlier one on the same node and path).
std::vector<NodePose> poseAt(const GltfContext& ctx, const std::vector<Animation>& animations,
                             int which, float t);

/// Node `index`'s local matrix T * R * S (glTF 2.0 §3.5.2) with the animated parts of `pose`
/// replacing the node's own translation, rotation and scale.
Mat4 animatedMatrix(const GltfContext& ctx, int index, const NodePose& pose);

}  // namespace tray

#include "gltf/gltf_animation.h"

#include <algorithm>
#include <cmath>

#include "gltf/gltf_accessors.h"

namespace tray {

namespace {

/// Spherical linear interpolation of unit quaternions on the shorter arc (glTF 2.0 Appendix C,
/// "Spherical Linear Interpolation": negate one end when the dot product is negative). In
/// double: the acos of a dot close to 1 loses digits in float.
std::vector<float> slerp(const float* a, const float* b, double u) {
  double d = 0;
  for (int i = 0; i < 4; ++i) d += double(a[i]) * b[i];
  const double sign = d < 0 ? -1.0 : 1.0;
  d = std::min(1.0, d * sign);
  double wa = 1 - u, wb = u * sign;
  if (d < 0.9995) {  // else nearly parallel: lerp (then normalise) avoids 0 / 0
    const double theta = std::acos(d), s = std::sin(theta);
    wa = std::sin((1 - u) * theta) / s;
    wb = sign * std::sin(u * theta) / s;
  }
  double q[4], len = 0;
  for (int i = 0; i < 4; ++i) {
    q[i] = wa * a[i] + wb * b[i];
    len += q[i] * q[i];
  }
  len = std::sqrt(len);
  std::vector<float> out(4);
  for (int i = 0; i < 4; ++i) out[size_t(i)] = float(q[i] / len);
  return out;
}

void normaliseQuaternion(std::vector<float>& q) {
  double len = 0;
  for (float c : q) len += double(c) * c;
  len = std::sqrt(len);
  if (len > 0)
    for (float& c : q) c = float(c / len);
}

bool isNormalizedInteger(const tinygltf::Accessor& a) {
  return a.normalized && a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT &&
         a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

/// Morph target count of the mesh on node `node`, or 0.
size_t targetCount(const GltfContext& ctx, int node) {
  const int mesh = ctx.model.nodes[size_t(node)].mesh;
  if (mesh < 0) return 0;
  const auto& prims = ctx.model.meshes[size_t(mesh)].primitives;
  return prims.empty() ? 0 : prims[0].targets.size();
}

AnimatedPath parsePath(const GltfContext& ctx, const std::string& path, const std::string& where) {
  if (path == "translation") return AnimatedPath::kTranslation;
  if (path == "rotation") return AnimatedPath::kRotation;
  if (path == "scale") return AnimatedPath::kScale;
  if (path == "weights") return AnimatedPath::kWeights;
  ctx.fail(where + " has unknown target path '" + path + "'");
}

Interpolation parseInterpolation(const GltfContext& ctx, const std::string& s,
                                 const std::string& where) {
  if (s == "LINEAR" || s.empty()) return Interpolation::kLinear;
  if (s == "STEP") return Interpolation::kStep;
  if (s == "CUBICSPLINE") return Interpolation::kCubicSpline;
  ctx.fail(where + " has unknown interpolation '" + s + "'");
}

/// Sampler input: float SCALAR times, finite and strictly increasing (glTF 2.0 §3.11).
std::vector<float> readTimes(const GltfContext& ctx, int accessor, const std::string& where) {
  if (accessor < 0 || size_t(accessor) >= ctx.model.accessors.size())
    ctx.fail(where + " refers to missing input accessor " + std::to_string(accessor));
  const auto& a = ctx.model.accessors[size_t(accessor)];
  const std::string name = nameOf("accessor", accessor, a.name);
  if (a.type != TINYGLTF_TYPE_SCALAR || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    ctx.fail(name + " (animation input) must be SCALAR float");
  if (a.count == 0) ctx.fail(name + " (animation input) has no keyframes");
  std::vector<float> t = readFloats(ctx, accessor);
  for (size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]))
      ctx.fail(name + " (animation input) has a NaN or infinite time at " + std::to_string(i));
    if (i > 0 && !(t[i] > t[i - 1]))
      ctx.fail(name + " (animation input) is not strictly increasing at keyframe " +
               std::to_string(i));
  }
  return t;
}

/// Sampler output for `path`: element type, component type and count checked (glTF 2.0 §3.11,
/// "Animation channel paths" table).
void readValues(const GltfContext& ctx, int accessor, AnimatedPath path, size_t weights,
                const std::string& where, Keyframes& k) {
  if (accessor < 0 || size_t(accessor) >= ctx.model.accessors.size())
    ctx.fail(where + " refers to missing output accessor " + std::to_string(accessor));
  const auto& a = ctx.model.accessors[size_t(accessor)];
  const std::string name = nameOf("accessor", accessor, a.name) + " (animation output)";
  const bool isFloat = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  bool ok;
  switch (path) {
    case AnimatedPath::kTranslation:
    case AnimatedPath::kScale:
      ok = a.type == TINYGLTF_TYPE_VEC3 && isFloat, k.width = 3;
      break;
    case AnimatedPath::kRotation:
      ok = a.type == TINYGLTF_TYPE_VEC4 && (isFloat || isNormalizedInteger(a)), k.width = 4;
      k.quaternion = true;
      break;
    default:
      ok = a.type == TINYGLTF_TYPE_SCALAR && (isFloat || isNormalizedInteger(a));
      k.width = int(weights);
  }
  if (!ok) ctx.fail(name + " has a type not allowed for its target path");
  const size_t perKey = (k.mode == Interpolation::kCubicSpline ? 3 : 1) *
                        (path == AnimatedPath::kWeights ? weights : 1);
  if (a.count != k.times.size() * perKey)
    ctx.fail(name + " has " + std::to_string(a.count) + " elements, expected " +
             std::to_string(k.times.size() * perKey) + " for " + std::to_string(k.times.size()) +
             " keyframes");
  k.values = readFloats(ctx, accessor);
  for (float v : k.values)
    if (!std::isfinite(v)) ctx.fail(name + " has a NaN or infinite value");
}

Animation readAnimation(const GltfContext& ctx, int index) {
  const tinygltf::Animation& g = ctx.model.animations[size_t(index)];
  const std::string where = nameOf("animation", index, g.name);
  Animation out{g.name, {}};
  for (size_t c = 0; c < g.channels.size(); ++c) {
    const auto& ch = g.channels[c];
    const std::string cw = where + " channel " + std::to_string(c);
    if (ch.sampler < 0 || size_t(ch.sampler) >= g.samplers.size())
      ctx.fail(cw + " refers to missing sampler " + std::to_string(ch.sampler));
    const AnimatedPath path = parsePath(ctx, ch.target_path, cw);
    if (ch.target_node < 0) continue;  // glTF 2.0 §3.11: no node, the channel is ignored
    if (size_t(ch.target_node) >= ctx.model.nodes.size())
      ctx.fail(cw + " targets missing node " + std::to_string(ch.target_node));
    const auto& node = ctx.model.nodes[size_t(ch.target_node)];
    const std::string nodeName = nameOf("node", ch.target_node, node.name);
    if (path != AnimatedPath::kWeights && !node.matrix.empty())
      ctx.fail(cw + " animates " + nodeName +
               ", which has a matrix (glTF 2.0 §3.11 allows TRS only)");
    const size_t weights = targetCount(ctx, ch.target_node);
    if (path == AnimatedPath::kWeights && weights == 0)
      ctx.fail(cw + " animates the morph weights of " + nodeName + ", which has no morph targets");

    const auto& s = g.samplers[size_t(ch.sampler)];
    const std::string sw = where + " sampler " + std::to_string(ch.sampler);
    AnimationChannel out1{ch.target_node, path, {}};
    out1.keys.mode = parseInterpolation(ctx, s.interpolation, sw);
    out1.keys.times = readTimes(ctx, s.input, sw);
    if (out1.keys.mode == Interpolation::kCubicSpline && out1.keys.times.size() < 2)
      ctx.fail(sw + " is CUBICSPLINE with fewer than 2 keyframes");
    readValues(ctx, s.output, path, weights, sw, out1.keys);
    out.channels.push_back(std::move(out1));
  }
  return out;
}

}  // namespace

std::vector<float> sampleKeyframes(const Keyframes& k, float t) {
  const size_t n = k.times.size(), w = size_t(k.width);
  const bool cubic = k.mode == Interpolation::kCubicSpline;
  // Value of key i: CUBICSPLINE stores (in-tangent, value, out-tangent) per key.
  auto value = [&](size_t i, size_t part) { return &k.values[(cubic ? 3 * i + part : i) * w]; };
  auto copy = [&](const float* v) {
    std::vector<float> out(v, v + w);
    if (k.quaternion && cubic) normaliseQuaternion(out);
    return out;
  };
  if (!(t > k.times.front())) return copy(value(0, 1));  // also catches NaN
  if (t >= k.times.back()) return copy(value(n - 1, 1));
  const auto next = std::upper_bound(k.times.begin(), k.times.end(), t);
  const size_t i = size_t(next - k.times.begin()) - 1;
  const double td = double(k.times[i + 1]) - k.times[i];
  const double u = (double(t) - k.times[i]) / td;
  if (k.mode == Interpolation::kStep) return copy(value(i, 1));
  if (k.mode == Interpolation::kLinear) {
    if (k.quaternion) return slerp(value(i, 1), value(i + 1, 1), u);
    std::vector<float> out(w);
    for (size_t c = 0; c < w; ++c)
      out[c] = float((1 - u) * value(i, 1)[c] + u * value(i + 1, 1)[c]);
    return out;
  }
  // Cubic Hermite spline (glTF 2.0 Appendix C): tangents scaled by the keyframe interval.
  const double u2 = u * u, u3 = u2 * u;
  const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2,
               h11 = u3 - u2;
  const float *v0 = value(i, 1), *b0 = value(i, 2), *v1 = value(i + 1, 1), *a1 = value(i + 1, 0);
  std::vector<float> out(w);
  for (size_t c = 0; c < w; ++c)
    out[c] = float(h00 * v0[c] + td * h10 * b0[c] + h01 * v1[c] + td * h11 * a1[c]);
  if (k.quaternion) normaliseQuaternion(out);
  return out;
}

std::vector<Animation> readAnimations(const GltfContext& ctx) {
  std::vector<Animation> out;
  for (size_t i = 0; i < ctx.model.animations.size(); ++i)
    out.push_back(readAnimation(ctx, int(i)));
  return out;
}

int chooseAnimation(const GltfContext& ctx, const std::vector<Animation>& animations,
                    const std::string& which) {
  if (which == "all") return -1;
  if (which.empty() || which == "first") return 0;  // poseAt skips none when there is none
  std::vector<std::string> names;
  for (const Animation& a : animations) names.push_back(a.name);
  if (const int i = findByNameOrIndex(names, which); i >= 0) return i;
  ctx.fail("--animation " + which + ": no such animation (the file has " +
           std::to_string(animations.size()) + listOfChoices(names) + "; or first, all)");
}

std::vector<NodePose> poseAt(const GltfContext& ctx, const std::vector<Animation>& animations,
                             int which, float t) {
  std::vector<NodePose> poses(ctx.model.nodes.size());
  for (size_t a = 0; a < animations.size(); ++a) {
    if (which >= 0 && size_t(which) != a) continue;
    for (const AnimationChannel& ch : animations[a].channels) {
      std::vector<float> v = sampleKeyframes(ch.keys, t);
      NodePose& p = poses[size_t(ch.node)];
      switch (ch.path) {
        case AnimatedPath::kTranslation:
          p.translation = Vec3{v[0], v[1], v[2]};
          break;
        case AnimatedPath::kScale:
          p.scale = Vec3{v[0], v[1], v[2]};
          break;
        case AnimatedPath::kRotation:
          p.rotation = std::move(v);
          break;
        case AnimatedPath::kWeights:
          p.weights = std::move(v);
      }
    }
  }
  return poses;
}

Mat4 animatedMatrix(const GltfContext& ctx, int index, const NodePose& pose) {
  const auto& n = ctx.model.nodes[size_t(index)];
  Vec3 t{0, 0, 0}, s{1, 1, 1};
  std::vector<double> q = n.rotation.empty() ? std::vector<double>{0, 0, 0, 1} : n.rotation;
  if (!n.translation.empty())
    t = {float(n.translation[0]), float(n.translation[1]), float(n.translation[2])};
  if (!n.scale.empty()) s = {float(n.scale[0]), float(n.scale[1]), float(n.scale[2])};
  if (pose.translation) t = *pose.translation;
  if (pose.scale) s = *pose.scale;
  if (pose.rotation) q.assign(pose.rotation->begin(), pose.rotation->end());
  // The node's own values were checked by localMatrix(); a sampled rotation is unit length
  // unless every key was zero.
  const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(len > 0)) ctx.fail(nameOf("node", index, n.name) + " is animated to a zero rotation");
  const Mat4 m =
      Mat4::translate(t) *
      Mat4::rotate(float(q[0] / len), float(q[1] / len), float(q[2] / len), float(q[3] / len)) *
      Mat4::scale(s);
  if (!m.isFinite()) ctx.fail(nameOf("node", index, n.name) + " animated transform overflows");
  return m;
}

}  // namespace tray

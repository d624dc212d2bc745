#include "gltf/gltf_deform.h"

#include <algorithm>
#include <cmath>

#include "gltf/gltf_accessors.h"

namespace tray {

namespace {

/// Embree silently drops primitives with coordinates beyond about 1.8e18 (as gltf_meshes.cpp).
constexpr float kMaxCoordinate = 1e18f;
/// Morph target vertices read over the whole file (each non-zero weight of each morphed node
/// reads its target again): a few seconds of work, so that many targets on many nodes cannot
/// keep a hostile file loading for hours. 4x the vertex cap of gltf_context.h.
constexpr size_t kMaxDisplacements = 4 * kMaxVertices;

int attribute(const tinygltf::Primitive& p, const char* semantic) {
  auto it = p.attributes.find(semantic);
  return it == p.attributes.end() ? -1 : it->second;
}

/// An accessor as `count` Vec3, checked VEC3 with `count` elements.
std::vector<Vec3> readVec3(const GltfContext& ctx, int accessor, size_t count,
                           const std::string& what) {
  const auto& a = ctx.model.accessors[size_t(accessor)];
  const std::string name = nameOf("accessor", accessor, a.name) + " (" + what + ")";
  if (a.type != TINYGLTF_TYPE_VEC3) ctx.fail(name + " must be VEC3");
  if (a.count != count)
    ctx.fail(name + " has " + std::to_string(a.count) + " elements for " + std::to_string(count) +
             " vertices");
  const std::vector<float> f = readFloats(ctx, accessor);
  std::vector<Vec3> v(count);
  for (size_t i = 0; i < count; ++i) {
    v[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    if (!isFinite(v[i])) ctx.fail(name + " has a NaN or infinite value at " + std::to_string(i));
  }
  return v;
}

Vec3 normalizedOrZero(const Vec3& v) {
  const float len = length(v);
  return len > 0 ? v / len : Vec3{0, 0, 0};
}

/// sum_i w_i M_i of affine matrices (the last row stays 0 0 0 1).
Mat4 blend(const std::vector<Mat4>& joints, const int* index, const float* weight, int n) {
  Mat4 m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      double s = 0;
      for (int k = 0; k < n; ++k) s += double(weight[k]) * joints[size_t(index[k])].m[r][c];
      m.m[r][c] = float(s);
    }
  return m;
}

/// Cofactor matrix of the upper 3x3: det(A) * A^-T, which maps normals without dividing by a
/// determinant that may be zero (glTF 2.0 §3.7.3.3 blends may collapse a vertex).
void cofactor(const Mat4& a, float c[3][3]) {
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) {
      const int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
      c[r][k] = a.m[r1][k1] * a.m[r2][k2] - a.m[r1][k2] * a.m[r2][k1];
    }
}

}  // namespace

std::vector<Mat4> worldMatrices(const GltfContext& ctx, const std::vector<Mat4>& local) {
  const auto& nodes = ctx.model.nodes;
  std::vector<int> parent(nodes.size(), -1);
  for (size_t i = 0; i < nodes.size(); ++i)
    for (int c : nodes[i].children) parent[size_t(c)] = int(i);
  std::vector<Mat4> world(nodes.size());
  std::vector<int> order;  // roots first, then children: parents before children
  for (size_t i = 0; i < nodes.size(); ++i)
    if (parent[i] < 0) order.push_back(int(i));
  for (size_t k = 0; k < order.size(); ++k)
    for (int c : nodes[size_t(order[k])].children) order.push_back(c);
  for (int n : order) {
    const int up = parent[size_t(n)];
    world[size_t(n)] = up < 0 ? local[size_t(n)] : world[size_t(up)] * local[size_t(n)];
  }
  return world;
}

Deformer::Deformer(const GltfContext& ctx, const std::vector<NodePose>& poses,
                   const std::vector<Mat4>& world)
    : ctx_(ctx) {
  const auto& model = ctx.model;
  weights_.resize(model.nodes.size());
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    const auto& node = model.nodes[i];
    if (node.mesh < 0) continue;
    const auto& mesh = model.meshes[size_t(node.mesh)];
    const size_t targets = mesh.primitives[0].targets.size();
    const std::string where = nameOf("mesh", node.mesh, mesh.name);
    for (size_t p = 1; p < mesh.primitives.size(); ++p)
      if (mesh.primitives[p].targets.size() != targets)
        ctx.fail(where + " primitives have different numbers of morph targets (glTF 2.0 §3.7.2.2)");
    if (targets == 0) continue;
    // glTF 2.0 §3.7.2.2: node.weights override mesh.weights; the animation overrides both.
    std::vector<float> w(targets, 0.0f);
    const std::vector<double>& given = node.weights.empty() ? mesh.weights : node.weights;
    if (!given.empty() && given.size() != targets)
      ctx.fail((node.weights.empty() ? where : nameOf("node", int(i), node.name)) + " has " +
               std::to_string(given.size()) + " morph weights for " + std::to_string(targets) +
               " targets");
    for (size_t k = 0; k < given.size(); ++k) w[k] = float(given[k]);
    if (i < poses.size() && poses[i].weights) w = *poses[i].weights;
    for (float x : w)
      if (!std::isfinite(x)) ctx.fail(nameOf("node", int(i), node.name) + " morph weight is NaN");
    weights_[i] = std::move(w);
  }
  for (size_t s = 0; s < model.skins.size(); ++s) {
    const auto& skin = model.skins[s];
    const std::string where = nameOf("skin", int(s), skin.name);
    if (skin.joints.empty()) ctx.fail(where + " has no joints");
    // Not read (joints are placed by their own nodes), but a reference all the same (glTF 2.0
    // §5.23: the id of a node): a skeleton node that does not exist is a broken file.
    if (skin.skeleton != -1 && (skin.skeleton < 0 || size_t(skin.skeleton) >= model.nodes.size()))
      ctx.fail(where + " names skeleton node " + std::to_string(skin.skeleton) +
               ", which does not exist");
    std::vector<float> ibm;
    if (skin.inverseBindMatrices >= 0) {
      if (size_t(skin.inverseBindMatrices) >= model.accessors.size())
        ctx.fail(where + " refers to missing accessor " + std::to_string(skin.inverseBindMatrices));
      const auto& a = model.accessors[size_t(skin.inverseBindMatrices)];
      if (a.type != TINYGLTF_TYPE_MAT4 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
          a.count < skin.joints.size())
        ctx.fail(nameOf("accessor", skin.inverseBindMatrices, a.name) +
                 " (inverseBindMatrices) must be MAT4 float with one matrix per joint");
      ibm = readFloats(ctx, skin.inverseBindMatrices);
    }
    std::vector<Mat4> joints;
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      const int n = skin.joints[j];
      if (n < 0 || size_t(n) >= model.nodes.size())
        ctx.fail(where + " refers to missing joint node " + std::to_string(n));
      Mat4 inverseBind;  // identity when absent (glTF 2.0 §3.7.3.1)
      if (!ibm.empty()) {
        double v[16];
        for (int k = 0; k < 16; ++k) v[k] = ibm[16 * j + size_t(k)];
        inverseBind = Mat4::fromColumnMajor(v);
      }
      const Mat4 m = world[size_t(n)] * inverseBind;
      if (!m.isFinite()) ctx.fail(where + " joint " + std::to_string(j) + " matrix overflows");
      joints.push_back(m);
    }
    joints_.push_back(std::move(joints));
  }
}

bool Deformer::skinned(int node) const {
  const auto& n = ctx_.model.nodes[size_t(node)];
  return n.skin >= 0 && n.mesh >= 0;
}

bool Deformer::deforms(int node) const {
  if (skinned(node)) return true;
  for (float w : weights_[size_t(node)])
    if (w != 0) return true;
  return false;
}

void Deformer::apply(int node, size_t primitive, TriangleMesh& mesh) const {
  morph(node, primitive, mesh);
  if (skinned(node)) skin(node, primitive, mesh);
  const std::string where = nameOf("node", node, ctx_.model.nodes[size_t(node)].name);
  for (const Vec3& p : mesh.positions)
    if (!isFinite(p) || maxComponent(abs(p)) > kMaxCoordinate)
      ctx_.fail(where + " deforms its mesh to a NaN, infinite or beyond-1e18 position");
  for (Vec3& n : mesh.normals) n = normalizedOrZero(n);
  for (Vec3& t : mesh.tangents) t = normalizedOrZero(t);
}

/// glTF 2.0 §3.7.2.2: each attribute becomes base + sum_i w_i * target_i.
void Deformer::morph(int node, size_t primitive, TriangleMesh& mesh) const {
  const std::vector<float>& w = weights_[size_t(node)];
  const int meshIndex = ctx_.model.nodes[size_t(node)].mesh;
  const auto& prim = ctx_.model.meshes[size_t(meshIndex)].primitives[primitive];
  const size_t n = mesh.positions.size();
  for (size_t t = 0; t < prim.targets.size() && t < w.size(); ++t) {
    if (w[t] == 0) continue;
    const auto& target = prim.targets[t];
    auto add = [&](const char* semantic, std::vector<Vec3>& v) {
      auto it = target.find(semantic);
      if (it == target.end() || v.size() != n) return;  // absent here or in the base
      if ((displacements_ += n) > kMaxDisplacements)
        ctx_.fail("morph targets applied exceed " + std::to_string(kMaxDisplacements) +
                  " vertex displacements (too many targets on too many nodes)");
      const std::vector<Vec3> d = readVec3(ctx_, it->second, n, std::string("morph ") + semantic);
      for (size_t i = 0; i < n; ++i) v[i] += w[t] * d[i];
    };
    add("POSITION", mesh.positions);
    add("NORMAL", mesh.normals);
    add("TANGENT", mesh.tangents);
  }
}

namespace {

/// Up to two sets of four influences per vertex (JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1), eight
/// slots each in `index` / `weight`; joints checked against the skin's `jointCount`.
void readInfluences(const GltfContext& ctx, int node, size_t primitive, size_t jointCount, size_t n,
                    std::vector<int>& index, std::vector<float>& weight) {
  const auto& gnode = ctx.model.nodes[size_t(node)];
  const auto& prim = ctx.model.meshes[size_t(gnode.mesh)].primitives[primitive];
  const std::string where =
      nameOf("node", node, gnode.name) + " skinned primitive " + std::to_string(primitive);
  index.assign(8 * n, 0);
  weight.assign(8 * n, 0.0f);
  for (int s = 0; s < 2; ++s) {
    const std::string set = std::to_string(s);
    const int j = attribute(prim, ("JOINTS_" + set).c_str());
    const int w = attribute(prim, ("WEIGHTS_" + set).c_str());
    if (j < 0 && w < 0) {
      if (s == 0) ctx.fail(where + " has no JOINTS_0 / WEIGHTS_0");
      break;
    }
    if (j < 0 || w < 0)
      ctx.fail(where + " has JOINTS_" + set + " and WEIGHTS_" + set + " unpaired");
    const std::vector<float> jf = readFloats(ctx, j), wf = readFloats(ctx, w);
    for (size_t v = 0; v < n; ++v)
      for (size_t k = 0; k < 4; ++k) {
        const float ji = jf[4 * v + k], wi = wf[4 * v + k];
        if (!(wi >= 0) || !std::isfinite(wi))
          ctx.fail(nameOf("accessor", w) + " (WEIGHTS_" + set +
                   ") has a negative or non-finite weight at vertex " + std::to_string(v));
        if (wi > 0 && ji >= float(jointCount))
          ctx.fail(nameOf("accessor", j) + " (JOINTS_" + set + ") joint " +
                   std::to_string(int(ji)) + " at vertex " + std::to_string(v) +
                   " is out of range (the skin has " + std::to_string(jointCount) + ")");
        index[8 * v + 4 * size_t(s) + k] = wi > 0 ? int(ji) : 0;
        weight[8 * v + 4 * size_t(s) + k] = wi;
      }
  }
}

/// Rescales weights whose sum is off 1 (counted in `rescaled`).
void normaliseWeights(float* w, size_t& rescaled) {
  double sum = 0;
  int nonZero = 0;
  for (int k = 0; k < 8; ++k) sum += w[k], nonZero += w[k] > 0;
  // The spec asks for sums "as close as reasonably possible to 1" without a number; the
  // Khronos glTF-Validator (ACCESSOR_WEIGHTS_NON_NORMALIZED) allows 0.0039216, just over one
  // unsigned-byte step, per pair of non-zero weights beyond the first two. Plus float rounding.
  const double tolerance = 1e-6 + 0.0039216 * ((std::max(nonZero, 1) - 1) / 2);
  if (std::fabs(sum - 1) <= tolerance) return;
  ++rescaled;
  if (sum > 0)
    for (int k = 0; k < 8; ++k) w[k] = float(w[k] / sum);
  else
    w[0] = 1;  // no influence at all: follow the first joint listed
}

Vec3 mul3(const float a[3][3], const Vec3& v) {
  return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z,
          a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
          a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
}

}  // namespace

/// Linear blend skinning (glTF 2.0 §3.7.3.3): each vertex by sum_k w_k * joint matrix k.
void Deformer::skin(int node, size_t primitive, TriangleMesh& mesh) const {
  const std::vector<Mat4>& joints = joints_[size_t(ctx_.model.nodes[size_t(node)].skin)];
  const size_t n = mesh.positions.size();
  std::vector<int> index;
  std::vector<float> weight;
  readInfluences(ctx_, node, primitive, joints.size(), n, index, weight);
  for (size_t v = 0; v < n; ++v) {
    normaliseWeights(&weight[8 * v], renormalised_);
    const Mat4 m = blend(joints, &index[8 * v], &weight[8 * v], 8);
    const float linear[3][3] = {{m.m[0][0], m.m[0][1], m.m[0][2]},
                                {m.m[1][0], m.m[1][1], m.m[1][2]},
                                {m.m[2][0], m.m[2][1], m.m[2][2]}};
    mesh.positions[v] = mul3(linear, mesh.positions[v]) + Vec3{m.m[0][3], m.m[1][3], m.m[2][3]};
    float c[3][3];
    cofactor(m, c);
    const float det = m.m[0][0] * c[0][0] + m.m[0][1] * c[0][1] + m.m[0][2] * c[0][2];
    if (v < mesh.normals.size())
      mesh.normals[v] = (det < 0 ? -1.0f : 1.0f) * mul3(c, mesh.normals[v]);
    if (v < mesh.tangents.size()) {
      mesh.tangents[v] = mul3(linear, mesh.tangents[v]);
      // A mirroring blend flips the bitangent's handedness relative to the mapped frame.
      if (det < 0 && v < mesh.tangentSigns.size()) mesh.tangentSigns[v] = -mesh.tangentSigns[v];
    }
  }
}

}  // namespace tray

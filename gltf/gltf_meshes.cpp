#include "gltf/gltf_meshes.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "gltf/gltf_accessors.h"
#include "gltf/gltf_variants.h"

namespace tray {

namespace {

/// Embree silently drops primitives with coordinates beyond about 1.8e18; refuse them instead.
constexpr float kMaxCoordinate = 1e18f;

int attribute(const tinygltf::Primitive& p, const char* semantic) {
  auto it = p.attributes.find(semantic);
  return it == p.attributes.end() ? -1 : it->second;
}

/// Vertex indices of triangle t of a list, strip or fan (glTF 2.0 §3.7.2.1, "Primitive
/// topology"): strips alternate winding so every triangle faces the same way.
void triangleOf(int mode, size_t t, const std::vector<uint32_t>& idx, uint32_t out[3]) {
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    bool odd = t % 2 == 1;
    out[0] = idx[t];
    out[1] = idx[t + (odd ? 2 : 1)];
    out[2] = idx[t + (odd ? 1 : 2)];
  } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    out[0] = idx[t + 1];
    out[1] = idx[t + 2];
    out[2] = idx[0];
  } else {
    for (int k = 0; k < 3; ++k) out[k] = idx[3 * t + k];
  }
}

/// Zeroes every `n`-float element with a non-finite component (counted): a bad normal must not
/// poison shading, and Scene::surface falls back to the geometric normal for zero ones.
std::vector<float> repaired(std::vector<float> f, int n, size_t& count) {
  for (size_t i = 0; i + n <= f.size(); i += size_t(n)) {
    bool finite = true;
    for (int c = 0; c < n; ++c) finite = finite && std::isfinite(f[i + c]);
    if (finite) continue;
    ++count;
    for (int c = 0; c < n; ++c) f[i + c] = 0.0f;
  }
  return f;
}

void readPositions(const GltfContext& ctx, int accessor, TriangleMesh& mesh) {
  std::vector<float> f = readFloats(ctx, accessor);
  mesh.positions.resize(f.size() / 3);
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    Vec3 p{f[3 * i], f[3 * i + 1], f[3 * i + 2]};
    if (!isFinite(p))
      ctx.fail(nameOf("accessor", accessor) + " (POSITION) has a NaN or infinite value at vertex " +
               std::to_string(i));
    if (maxComponent(abs(p)) > kMaxCoordinate)
      ctx.fail(nameOf("accessor", accessor) +
               " (POSITION) has a coordinate beyond 1e18 at vertex " + std::to_string(i));
    mesh.positions[i] = p;
  }
}

/// COLOR_0 (glTF 2.0 §3.7.2.1): VEC3 or VEC4 of float or normalized unsigned byte / short,
/// linear; readFloats maps the integers to [0, 1]. Alpha only for VEC4.
void readColors(const GltfContext& ctx, int accessor, TriangleMesh& mesh, MeshStats& stats) {
  const int n = ctx.model.accessors[size_t(accessor)].type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
  std::vector<float> f = repaired(readFloats(ctx, accessor), n, stats.repairedAttributes);
  for (size_t i = 0; i + size_t(n) <= f.size(); i += size_t(n)) {
    mesh.colors.push_back({f[i], f[i + 1], f[i + 2]});
    if (n == 4) mesh.colorAlphas.push_back(std::clamp(f[i + 3], 0.0f, 1.0f));
  }
}

void readOtherAttributes(const GltfContext& ctx, const tinygltf::Primitive& p, TriangleMesh& mesh,
                         MeshStats& stats) {
  if (int a = attribute(p, "NORMAL"); a >= 0) {
    std::vector<float> f = repaired(readFloats(ctx, a), 3, stats.repairedAttributes);
    for (size_t i = 0; i + 3 <= f.size(); i += 3)
      mesh.normals.push_back({f[i], f[i + 1], f[i + 2]});
  }
  if (int a = attribute(p, "TEXCOORD_0"); a >= 0) {
    std::vector<float> f = repaired(readFloats(ctx, a), 2, stats.repairedAttributes);
    for (size_t i = 0; i + 2 <= f.size(); i += 2) mesh.uvs.push_back({f[i], f[i + 1]});
  }
  if (int a = attribute(p, "TEXCOORD_1"); a >= 0) {
    std::vector<float> f = repaired(readFloats(ctx, a), 2, stats.repairedAttributes);
    for (size_t i = 0; i + 2 <= f.size(); i += 2) mesh.uvs1.push_back({f[i], f[i + 1]});
  }
  if (int a = attribute(p, "COLOR_0"); a >= 0) readColors(ctx, a, mesh, stats);
  if (int a = attribute(p, "TANGENT"); a >= 0) {
    std::vector<float> f = repaired(readFloats(ctx, a), 4, stats.repairedAttributes);
    for (size_t i = 0; i + 4 <= f.size(); i += 4) {
      mesh.tangents.push_back({f[i], f[i + 1], f[i + 2]});
      // glTF 2.0 §3.7.2.1: w is +1 or -1, the handedness of the bitangent.
      mesh.tangentSigns.push_back(f[i + 3] < 0 ? -1.0f : 1.0f);
    }
  }
}

/// Builds one primitive's mesh; false if it has no triangle left.
bool convertPrimitive(const GltfContext& ctx, const tinygltf::Primitive& p,
                      const std::string& where, MeshStats& stats, TriangleMesh& mesh,
                      const std::function<void(TriangleMesh&)>& deform) {
  const int mode = p.mode == -1 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  const int position = attribute(p, "POSITION");
  const size_t vertexCount = ctx.model.accessors[size_t(position)].count;
  if (vertexCount > kMaxVertices - stats.vertices)
    ctx.fail(where + " exceeds the limit of " + std::to_string(kMaxVertices) + " vertices");
  stats.vertices += vertexCount;

  const size_t n = p.indices >= 0 ? ctx.model.accessors[size_t(p.indices)].count : vertexCount;
  size_t triangles;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (n % 3 != 0)
      ctx.fail(where + " has " + std::to_string(n) + " vertices, not a multiple of 3");
    triangles = n / 3;
  } else {
    if (n < 3) ctx.fail(where + " has fewer than 3 vertices for a strip or fan");
    triangles = n - 2;
  }
  if (triangles > kMaxTriangles - stats.triangles)
    ctx.fail(where + " exceeds the limit of " + std::to_string(kMaxTriangles) + " triangles");

  std::vector<uint32_t> idx;
  if (p.indices >= 0) {
    idx = readIndices(ctx, p.indices);
    for (size_t i = 0; i < idx.size(); ++i)
      if (idx[i] >= vertexCount)
        ctx.fail(nameOf("accessor", p.indices) + " (indices) value " + std::to_string(idx[i]) +
                 " at position " + std::to_string(i) + " is out of range (" +
                 std::to_string(vertexCount) + " vertices)");
  } else {
    idx.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) idx[i] = uint32_t(i);
  }
  readPositions(ctx, position, mesh);
  readOtherAttributes(ctx, p, mesh, stats);
  if (deform) deform(mesh);  // before triangles are tested for zero area

  mesh.indices.reserve(3 * triangles);
  for (size_t t = 0; t < triangles; ++t) {
    uint32_t v[3];
    triangleOf(mode, t, idx, v);
    const Vec3 &a = mesh.positions[v[0]], &b = mesh.positions[v[1]], &c = mesh.positions[v[2]];
    // !(x > 0) also catches a NaN area from coordinates whose products overflow.
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] || !(lengthSquared(cross(b - a, c - a)) > 0)) {
      ++stats.degenerateTriangles;
      continue;
    }
    mesh.indices.insert(mesh.indices.end(), v, v + 3);
  }
  stats.triangles += mesh.triangleCount();
  return mesh.triangleCount() > 0;
}

}  // namespace

std::vector<TriangleMesh> convertMesh(const GltfContext& ctx, int index, int defaultMaterial,
                                      MeshStats& stats, const VertexHook& deform) {
  const tinygltf::Mesh& g = ctx.model.meshes[size_t(index)];
  std::vector<TriangleMesh> out;
  for (size_t i = 0; i < g.primitives.size(); ++i) {
    const tinygltf::Primitive& p = g.primitives[i];
    int mode = p.mode == -1 ? TINYGLTF_MODE_TRIANGLES : p.mode;
    if (mode < TINYGLTF_MODE_TRIANGLES) {
      ++stats.pointAndLinePrimitives;
      continue;
    }
    if (attribute(p, "POSITION") < 0) {
      ++stats.primitivesWithoutPosition;
      continue;
    }
    TriangleMesh mesh;
    // Appended piecewise: GCC 12 warns falsely (-Wrestrict) about "literal" + std::string&&.
    mesh.name = g.name.empty() ? nameOf("mesh", index) : g.name;
    if (g.primitives.size() > 1) mesh.name.append("/").append(std::to_string(i));
    const int material = variantMaterial(p, ctx.variant);  // --variant, else p.material
    mesh.material = material >= 0 ? material : defaultMaterial;
    std::string where = nameOf("mesh", index, g.name) + " primitive " + std::to_string(i);
    std::function<void(TriangleMesh&)> hook;
    if (deform) hook = [&deform, i](TriangleMesh& m) { deform(i, m); };
    if (convertPrimitive(ctx, p, where, stats, mesh, hook)) out.push_back(std::move(mesh));
  }
  return out;
}

}  // namespace tray

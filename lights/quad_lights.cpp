#include "lights/quad_lights.h"

#include <array>
#include <cmath>
#include <map>
#include <unordered_map>

#include "core/front_face.h"

namespace tray {

namespace {

/// Vertex ids by object-space position: glTF splits vertices wherever normals or UVs differ,
/// so triangles of one quad often share positions, not indices.
std::vector<uint32_t> weldedIds(const TriangleMesh& mesh) {
  std::map<std::array<float, 3>, uint32_t> ids;
  std::vector<uint32_t> out(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const Vec3& p = mesh.positions[i];
    out[i] = ids.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(ids.size())).first->second;
  }
  return out;
}

/// Whether the triangles a b c and b a d (sharing the edge a b) form a rectangle with
/// diagonal a b, within the tolerance (findMeshRectangles).
bool formRectangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, float tolerance) {
  const Vec3 ca = a - c, cb = b - c;
  const float diagonal = length(a - b), la = length(ca), lb = length(cb);
  if (!(diagonal > 0) || !(la > 0) || !(lb > 0)) return false;
  return length(c + d - a - b) <= tolerance * diagonal &&
         std::fabs(dot(ca, cb)) <= tolerance * la * lb;
}

}  // namespace

std::vector<MeshRectangle> findMeshRectangles(const TriangleMesh& mesh, const Transform& toWorld,
                                              float tolerance) {
  std::vector<MeshRectangle> out;
  const size_t n = mesh.triangleCount();
  const std::vector<uint32_t> id = weldedIds(mesh);
  std::vector<bool> paired(n, false);
  // Edge (lower id, higher id) -> the first unpaired triangle seen with it.
  std::unordered_map<uint64_t, uint32_t> edges;
  const auto key = [](uint32_t u, uint32_t v) {
    return u < v ? uint64_t(u) << 32 | v : uint64_t(v) << 32 | u;
  };
  for (uint32_t t = 0; t < n; ++t) {
    const uint32_t* idx = &mesh.indices[3 * size_t(t)];
    for (int e = 0; e < 3 && !paired[t]; ++e) {
      const uint32_t i = idx[e], j = idx[(e + 1) % 3], k = idx[(e + 2) % 3];
      const auto [it, inserted] = edges.emplace(key(id[i], id[j]), t);
      if (inserted || paired[it->second]) continue;
      const uint32_t s = it->second;
      const uint32_t* sdx = &mesh.indices[3 * size_t(s)];
      // s's vertex off the shared edge.
      uint32_t o = sdx[0];
      for (int m = 0; m < 3; ++m)
        if (id[sdx[m]] != id[i] && id[sdx[m]] != id[j]) o = sdx[m];
      const Vec3 a = toWorld.point(mesh.positions[i]), b = toWorld.point(mesh.positions[j]);
      const Vec3 c = toWorld.point(mesh.positions[o]), d = toWorld.point(mesh.positions[k]);
      const Vec3 ns = triangleFrontNormal(toWorld, mesh.positions[sdx[0]], mesh.positions[sdx[1]],
                                          mesh.positions[sdx[2]]);
      const Vec3 nt = triangleFrontNormal(toWorld, mesh.positions[idx[0]], mesh.positions[idx[1]],
                                          mesh.positions[idx[2]]);
      if (!(dot(ns, nt) > 0) || !formRectangle(a, b, c, d, tolerance)) continue;
      // Corner c, edges to a and b; b's made exactly perpendicular to a's (the sampler's frame).
      const Vec3 ex = a - c, ey0 = b - c;
      const Vec3 ey = ey0 - (dot(ey0, ex) / dot(ex, ex)) * ex;
      out.push_back({s, t, c, ex, ey});
      paired[s] = paired[t] = true;
    }
  }
  return out;
}

}  // namespace tray

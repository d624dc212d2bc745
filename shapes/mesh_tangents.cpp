#include "shapes/mesh_tangents.h"

#include <cmath>

#include "core/sampling.h"

namespace tray {

namespace {

float angleBetween(const Vec3& a, const Vec3& b) {
  float la = length(a), lb = length(b);
  if (!(la > 0 && lb > 0)) return 0;
  return std::acos(std::clamp(dot(a, b) / (la * lb), -1.0f, 1.0f));
}

Vec3 unitOrZero(const Vec3& v) {
  float len = length(v);
  return len > 0 && std::isfinite(len) ? v / len : Vec3(0.0f);
}

}  // namespace

void computeTangents(TriangleMesh& mesh, int set) {
  const std::vector<Vec2>& uvs = set == 1 && !mesh.uvs1.empty() ? mesh.uvs1 : mesh.uvs;
  const size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || uvs.size() != n) return;
  std::vector<Vec3> sum(n, Vec3(0.0f));
  std::vector<float> handedness(n, 0.0f);
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const uint32_t* v = &mesh.indices[3 * t];
    const Vec3 e1 = mesh.positions[v[1]] - mesh.positions[v[0]];
    const Vec3 e2 = mesh.positions[v[2]] - mesh.positions[v[0]];
    const float du1 = uvs[v[1]].x - uvs[v[0]].x, dv1 = uvs[v[1]].y - uvs[v[0]].y;
    const float du2 = uvs[v[2]].x - uvs[v[0]].x, dv2 = uvs[v[2]].y - uvs[v[0]].y;
    const float det = du1 * dv2 - du2 * dv1;
    if (!(std::fabs(det) > 1e-20f)) continue;  // no uv area: no direction to follow
    const Vec3 dpdu = (dv2 * e1 - dv1 * e2) / det, dpdv = (du1 * e2 - du2 * e1) / det;
    for (int k = 0; k < 3; ++k) {
      const Vec3 nv = unitOrZero(mesh.normals[v[k]]);
      Vec3 tk = dpdu - nv * dot(nv, dpdu);
      float len = length(tk);
      if (!(len > 0) || !std::isfinite(len)) continue;
      const Vec3 a = mesh.positions[v[(k + 1) % 3]] - mesh.positions[v[k]];
      const Vec3 b = mesh.positions[v[(k + 2) % 3]] - mesh.positions[v[k]];
      const float w = angleBetween(a, b);
      sum[v[k]] += (w / len) * tk;
      handedness[v[k]] += dot(cross(nv, tk), dpdv) < 0 ? w : -w;
    }
  }
  mesh.tangents.assign(n, Vec3(0.0f));
  mesh.tangentSigns.assign(n, 1.0f);
  for (size_t i = 0; i < n; ++i) {
    float len = length(sum[i]);
    if (len > 0 && std::isfinite(len)) {
      mesh.tangents[i] = sum[i] / len;
    } else if (Vec3 nv = unitOrZero(mesh.normals[i]); !isBlack(nv)) {
      Vec3 b;  // isolated or degenerate: any tangent perpendicular to the normal
      orthonormalBasis(nv, mesh.tangents[i], b);
    } else {
      mesh.tangents[i] = {1.0f, 0.0f, 0.0f};
    }
    mesh.tangentSigns[i] = handedness[i] < 0 ? -1.0f : 1.0f;
  }
}

}  // namespace tray

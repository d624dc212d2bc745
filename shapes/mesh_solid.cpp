#include "shapes/mesh_solid.h"

#include <algorithm>
#include <array>
#include <map>

#include "core/error.h"

namespace tray {
namespace {

/// Welds vertices by exact position: glTF meshes duplicate vertices along hard edges (the
/// Khronos Box has 24 for 8 corners) though the surface is closed.
std::vector<uint32_t> weldedIds(const std::vector<Vec3>& positions) {
  std::map<std::array<float, 3>, uint32_t> ids;
  std::vector<uint32_t> out(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    const Vec3& p = positions[i];
    out[i] = ids.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(ids.size())).first->second;
  }
  return out;
}

/// Number of edges not matched by exactly one edge running the other way.
size_t openEdges(const TriangleMesh& m) {
  std::vector<uint32_t> id = weldedIds(m.positions);
  std::map<std::pair<uint32_t, uint32_t>, int> balance;  // +1 per a->b, -1 per b->a (a < b)
  for (size_t t = 0; t < m.triangleCount(); ++t)
    for (int e = 0; e < 3; ++e) {
      uint32_t a = id[m.indices[3 * t + e]], b = id[m.indices[3 * t + (e + 1) % 3]];
      if (a == b) continue;
      balance[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
    }
  return size_t(
      std::count_if(balance.begin(), balance.end(), [](const auto& kv) { return kv.second != 0; }));
}

/// Six times the signed volume (divergence theorem): positive for outward winding.
double signedVolume6(const TriangleMesh& m) {
  double v = 0;
  for (size_t t = 0; t < m.triangleCount(); ++t) {
    const Vec3 &a = m.positions[m.indices[3 * t]], &b = m.positions[m.indices[3 * t + 1]],
               &c = m.positions[m.indices[3 * t + 2]];
    v += double(a.x) * (double(b.y) * c.z - double(b.z) * c.y) -
         double(a.y) * (double(b.x) * c.z - double(b.z) * c.x) +
         double(a.z) * (double(b.x) * c.y - double(b.y) * c.x);
  }
  return v;
}

/// A boundary crossing found by the all-hits query, before pairing.
struct MeshCrossing {
  Crossing crossing;
  int sign;  ///< +1 entering, -1 leaving
};

}  // namespace

MeshSolid::MeshSolid(TriangleMesh mesh, const AcceleratorFactory& accelerator) {
  const std::string what = "mesh '" + mesh.name + "' used as a CSG solid";
  if (mesh.triangleCount() == 0 || mesh.indices.size() % 3 != 0)
    throw Error(what + " has no triangles");
  for (uint32_t i : mesh.indices)
    if (i >= mesh.positions.size()) throw Error(what + " has an index out of range");
  if (size_t open = openEdges(mesh))
    throw Error(what + " is not closed and consistently wound (" + std::to_string(open) +
                " unmatched edges)");
  if (signedVolume6(mesh) < 0)  // wound inward: turn it outward
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
      std::swap(mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
  bounds_ = mesh.bounds();
  scene_.meshes.push_back(std::move(mesh));
  scene_.meshes[0].material = 0;
  Primitive p;
  p.kind = Primitive::Kind::kMesh;
  p.mesh = 0;
  p.name = scene_.meshes[0].name;
  scene_.primitives.push_back(p);
  scene_.finalize();
  accel_ = accelerator(scene_);
}

Vec3 MeshSolid::triangleNormal(uint32_t i) const {
  const TriangleMesh& m = mesh();
  const Vec3 &a = m.positions[m.indices[3 * i]], &b = m.positions[m.indices[3 * i + 1]],
             &c = m.positions[m.indices[3 * i + 2]];
  return cross(b - a, c - a);
}

Vec2 MeshSolid::uvAt(const Hit& h) const {
  const TriangleMesh& m = mesh();
  if (m.uvs.empty()) return {h.b1, h.b2};
  const Vec2 &a = m.uvs[m.indices[3 * h.triangle]], &b = m.uvs[m.indices[3 * h.triangle + 1]],
             &c = m.uvs[m.indices[3 * h.triangle + 2]];
  float b0 = 1 - h.b1 - h.b2;
  return {b0 * a.x + h.b1 * b.x + h.b2 * c.x, b0 * a.y + h.b1 * b.y + h.b2 * c.y};
}

bool MeshSolid::intersect(const Ray& ray, Hit& hit) const {
  Hit h;
  if (!accel_->intersect(ray, h)) return false;
  hit.t = h.t;
  hit.normal = triangleNormal(h.triangle);
  hit.uv = uvAt(h);
  return true;
}

void MeshSolid::intervals(const Ray& ray, std::vector<Interval>& out) const {
  // Embree traces only t >= 0: the whole line is the ray forwards plus the ray backwards,
  // both from the same origin so no precision is lost.
  std::vector<MeshCrossing> xs;
  std::vector<Hit> hits;
  for (float dir : {1.0f, -1.0f}) {
    accel_->allHits(Ray{ray.o, dir * ray.d, 0.0f, kInfinity}, hits);
    for (const Hit& h : hits) {
      if (dir < 0 && h.t == 0.0f) continue;  // already found forwards
      Vec3 n = triangleNormal(h.triangle);
      float dn = dot(ray.d, n);
      if (dn == 0.0f) continue;  // grazing along the plane of the triangle: no crossing
      xs.push_back({{dir * h.t, n, uvAt(h), -1}, dn < 0 ? 1 : -1});
    }
  }
  // At equal t an entry goes first, so a ray touching a silhouette edge (entering and
  // leaving at once) makes a zero-length interval rather than a lost exit.
  std::sort(xs.begin(), xs.end(), [](const MeshCrossing& a, const MeshCrossing& b) {
    return a.crossing.t != b.crossing.t ? a.crossing.t < b.crossing.t : a.sign > b.sign;
  });
  // A ray through an edge or a vertex hits every triangle meeting there: successive crossings
  // of the same sign this close are one crossing. Then pair by winding number.
  const float kSameHit = 1e-6f, scale = length(ray.o) / length(ray.d);
  int winding = 0;
  Interval current;
  for (size_t i = 0; i < xs.size(); ++i) {
    const MeshCrossing& x = xs[i];
    if (i > 0 && xs[i - 1].sign == x.sign &&
        x.crossing.t - xs[i - 1].crossing.t <= kSameHit * (scale + std::fabs(x.crossing.t)))
      continue;
    if (x.sign > 0 && winding++ == 0) current.enter = x.crossing;
    if (x.sign < 0 && winding > 0 && --winding == 0) {
      current.exit = x.crossing;
      out.push_back(current);
    }
  }
  // A closed mesh ends every interval; an unmatched entry (numerical loss) is dropped rather
  // than extended to infinity.
}

}  // namespace tray

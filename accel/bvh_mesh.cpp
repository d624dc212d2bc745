#include "accel/bvh_mesh.h"

#include "accel/bvh_traversal.h"
#include "accel/bvh_triangle.h"

namespace tray {
namespace {

void vertices(const TriangleMesh& m, uint32_t tri, Vec3& p0, Vec3& p1, Vec3& p2) {
  p0 = m.positions[m.indices[3 * tri]];
  p1 = m.positions[m.indices[3 * tri + 1]];
  p2 = m.positions[m.indices[3 * tri + 2]];
}

}  // namespace

MeshBvh::MeshBvh(const TriangleMesh& mesh, const BvhBuildOptions& options, bool hierarchy)
    : mesh_(mesh), hierarchy_(hierarchy) {
  const uint32_t n = uint32_t(mesh.triangleCount());
  std::vector<BvhTriangle> tris(n);
  std::vector<Bounds3> boxes(n);
  for (uint32_t i = 0; i < n; ++i) {
    BvhTriangle& t = tris[i];
    vertices(mesh, i, t.p0, t.p1, t.p2);
    t.index = i;
    boxes[i].extend(t.p0);
    boxes[i].extend(t.p1);
    boxes[i].extend(t.p2);
    if (boxes[i].finite()) bounds_.extend(boxes[i]);
  }
  if (!hierarchy_) {
    for (uint32_t i = 0; i < n; ++i)
      if (boxes[i].finite()) triangles_.push_back(tris[i]);
    triangles_.shrink_to_fit();
    return;
  }
  bvh_ = buildBvh(boxes, options);
  triangles_.reserve(bvh_.primitives.size());
  for (uint32_t id : bvh_.primitives) triangles_.push_back(tris[id]);
  // The leaf ranges now index triangles_ directly; the id list is no longer needed.
  bvh_.primitives = {};
}

template <class OnHit>
bool MeshBvh::forEachCandidate(const Ray& ray, const float& tmax, OnHit&& onHit) const {
  const WatertightRay wr = prepareWatertight(ray.o, ray.d);
  auto leaf = [&](uint32_t first, uint32_t count) {
    for (uint32_t k = first; k < first + count; ++k) {
      const BvhTriangle& tri = triangles_[k];
      float t, b1, b2;
      if (intersectWatertight(wr, tri.p0, tri.p1, tri.p2, ray.tmin, tmax, t, b1, b2) &&
          onHit(tri, t, b1, b2))
        return true;
    }
    return false;
  };
  if (!hierarchy_) return leaf(0, uint32_t(triangles_.size()));
  return traverseBvh(bvh_, prepareBvhRay(ray.o, ray.d), ray.tmin, tmax, leaf);
}

bool MeshBvh::intersect(const Ray& ray, float& tmax, Hit& hit) const {
  bool found = false;
  forEachCandidate(ray, tmax, [&](const BvhTriangle& tri, float t, float b1, float b2) {
    tmax = t;
    hit = Hit{};
    hit.t = t;
    hit.triangle = tri.index;
    hit.b1 = b1;
    hit.b2 = b2;
    found = true;
    return false;
  });
  return found;
}

bool MeshBvh::occluded(const Ray& ray, uint32_t& triangle) const {
  return forEachCandidate(ray, ray.tmax, [&](const BvhTriangle& tri, float, float, float) {
    triangle = tri.index;
    return true;
  });
}

void MeshBvh::allHits(const Ray& ray, uint32_t primitive, std::vector<Hit>& hits) const {
  forEachCandidate(ray, ray.tmax, [&](const BvhTriangle& tri, float t, float b1, float b2) {
    Hit h;
    h.t = t;
    h.primitive = primitive;
    h.triangle = tri.index;
    h.b1 = b1;
    h.b2 = b2;
    hits.push_back(h);
    return false;
  });
}

bool MeshBvh::occludedBy(const Ray& ray, uint32_t triangle) const {
  if (triangle >= mesh_.triangleCount()) return false;
  Vec3 p0, p1, p2;
  vertices(mesh_, triangle, p0, p1, p2);
  float t, b1, b2;
  return intersectWatertight(prepareWatertight(ray.o, ray.d), p0, p1, p2, ray.tmin, ray.tmax, t, b1,
                             b2);
}

}  // namespace tray

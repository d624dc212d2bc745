#include "core/scene.h"

#include "core/error.h"
#include "core/front_face.h"
#include "core/motion.h"

namespace tray {

void Scene::finalize() {
  if (materials.empty()) {
    Material m;
    m.name = "default";
    m.metallic = 0.0f;
    m.baseColor = Color(0.8f);
    m.phong = phongFromPbr(m);
    materials.push_back(m);
  }
  auto check = [&](int mat, const std::string& what) {
    if (mat < 0 || size_t(mat) >= materials.size())
      throw Error(what + " refers to material " + std::to_string(mat) + " which does not exist");
  };
  for (auto& m : meshes) check(m.material, "mesh '" + m.name + "'");
  for (auto& p : primitives) {
    if (p.kind == Primitive::Kind::kMesh && p.mesh >= meshes.size())
      throw Error("primitive '" + p.name + "' refers to a missing mesh");
    if (p.kind == Primitive::Kind::kShape && !p.shape)
      throw Error("primitive '" + p.name + "' has no shape");
    if (p.kind == Primitive::Kind::kShape) check(p.material, "shape '" + p.name + "'");
  }
}

bool Scene::moving() const {
  for (const auto& p : primitives)
    if (!p.motion.empty() || (p.kind == Primitive::Kind::kMesh && p.mesh < meshes.size() &&
                              !meshes[p.mesh].positionSteps.empty()))
      return true;
  return false;
}

Bounds3 Scene::bounds() const {
  Bounds3 b;
  for (const auto& p : primitives) {
    Bounds3 local = p.kind == Primitive::Kind::kMesh ? meshes[p.mesh].bounds() : p.shape->bounds();
    if (local.finite()) b.extend(motionBounds(p, local));  // over the whole shutter
  }
  return b;
}

bool Scene::intersectShape(uint32_t i, const Ray& r, Hit& hit) const {
  const Primitive& prim = primitives[i];
  Transform moved;
  const Transform* toWorld = placementAt(prim, r.time, moved);
  if (!toWorld) return false;
  Ray local{toWorld->inversePoint(r.o), toWorld->inverseVector(r.d), r.tmin, r.tmax};
  Hit h;
  if (!prim.shape->intersect(local, h)) return false;
  hit = h;
  hit.primitive = i;
  return true;
}

SurfacePoint Scene::surface(const Ray& ray, const Hit& hit) const {
  const Primitive& prim = primitives[hit.primitive];
  SurfacePoint s;
  s.primitive = hit.primitive;
  s.time = ray.time;
  // A moving primitive is shaded where the ray found it. Its matrix at the hit's time was
  // invertible, or the accelerator would have reported no hit.
  Transform moved;
  const Transform* placed = placementAt(prim, ray.time, moved);
  const Transform& toWorld = placed ? *placed : moved;
  if (prim.kind == Primitive::Kind::kShape) {
    // Recompute the point in object space and project it back onto the surface: the world
    // point o + t d loses precision far from the origin.
    Ray local{toWorld.inversePoint(ray.o), toWorld.inverseVector(ray.d)};
    Vec3 pl = prim.shape->refine(local.o + hit.t * local.d);
    s.p = toWorld.point(pl);
    // Copied from a local, not from s.ng: reading back a just-stored Vec3 as one wider load
    // cannot be store-forwarded (a stall per hit; see setSpawnRay in core/ray.h).
    const Vec3 ng = normalize(toWorld.normal(hit.normal));
    s.ng = ng;
    s.n = ng;
    s.front = ng;  // outward
    s.uv = hit.uv;
    s.material = hit.material >= 0 ? hit.material : prim.material;
  } else {
    const TriangleMesh& m = meshes[prim.mesh];
    uint32_t i0 = m.indices[3 * hit.triangle], i1 = m.indices[3 * hit.triangle + 1],
             i2 = m.indices[3 * hit.triangle + 2];
    float b0 = 1.0f - hit.b1 - hit.b2;
    // A deforming mesh: its triangle where the ray found it.
    const Vec3 p0 = vertexAt(m, i0, ray.time), p1 = vertexAt(m, i1, ray.time),
               p2 = vertexAt(m, i2, ray.time);
    s.p = toWorld.point(b0 * p0 + hit.b1 * p1 + hit.b2 * p2);
    const Vec3 ng = normalize(triangleFrontNormal(toWorld, p0, p1, p2));
    s.front = ng;
    if (!m.normals.empty()) {
      Vec3 nl = b0 * m.normals[i0] + hit.b1 * m.normals[i1] + hit.b2 * m.normals[i2];
      Vec3 nw = toWorld.normal(nl);
      float len = length(nw);
      const Vec3 n = len > 0 && std::isfinite(len) ? nw / len : ng;
      s.n = n;
      // Shading keeps the geometric normal on the shading normal's side (flat fallback
      // otherwise); the front face for emission stays the winding's (s.front).
      s.ng = dot(n, ng) < 0 ? -ng : ng;
    } else {
      s.n = ng;
      s.ng = ng;
    }
    if (!m.uvs.empty()) {
      s.uv = {b0 * m.uvs[i0].x + hit.b1 * m.uvs[i1].x + hit.b2 * m.uvs[i2].x,
              b0 * m.uvs[i0].y + hit.b1 * m.uvs[i1].y + hit.b2 * m.uvs[i2].y};
    } else {
      s.uv = {hit.b1, hit.b2};
    }
    s.material = hit.material >= 0 ? hit.material : m.material;
  }
  s.frontFace = dot(ray.d, s.ng) < 0;  // after the stores above retire: no stall measured
  return s;
}

}  // namespace tray

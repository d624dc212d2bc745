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
    if (p.instances && (p.kind != Primitive::Kind::kMesh || !p.motion.empty() ||
                        !meshes[p.mesh].positionSteps.empty()))
      throw Error("primitive '" + p.name + "': an instance array places a static mesh only");
    // Lights and alpha filters name a placed primitive, not an instance: such meshes stay one
    // Primitive per instance (gltf/gltf_scene_graph.cpp, asArray).
    if (p.instances) {
      const Material& m = materials[size_t(meshes[p.mesh].material)];
      if (m.alphaMode != AlphaMode::kOpaque || !isBlack(m.emissive) || m.emissiveTexture.valid())
        throw Error("primitive '" + p.name +
                    "': an instance array's mesh must be opaque and not emissive");
    }
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
    if (!local.finite()) continue;
    if (p.instances)
      for (uint32_t j = 0; j < p.instances->size(); ++j)
        b.extend(p.instances->placement(j).bounds(local));
    else
      b.extend(motionBounds(p, local));  // over the whole shutter
  }
  return b;
}

std::string Scene::objectName(uint32_t i, uint32_t instance) const {
  const Primitive& p = primitives[i];
  if (!p.instances) return p.name.empty() ? "node" + std::to_string(p.objectId) : p.name;
  std::string name = p.instances->name;
  name += '#';
  name += std::to_string(p.instances->index(instance));
  return name;
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

namespace {

// The surface of an analytic shape placed by toWorld.
void shapeSurface(const Primitive& prim, const Transform& toWorld, const Ray& ray, const Hit& hit,
                  SurfacePoint& s) {
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
  // Curves and subdivision surfaces (shapes/curves.h, subdivision.h) say more than hit.normal.
  if (ShapeShading sh; prim.shape->shade(local, hit, sh)) {
    s.ng = s.front = normalize(toWorld.normal(sh.ng));
    s.n = normalize(toWorld.normal(sh.n));
    if (!isBlack(sh.tangent)) s.tangent = normalize(toWorld.vector(sh.tangent));
  }
}

// The surface of a mesh triangle placed by toWorld. Inlined into Scene::surface's static path:
// the call cost 9 instructions per hit (callgrind, Cornell box).
[[gnu::always_inline]] inline void meshSurface(const TriangleMesh& m, const Transform& toWorld,
                                               const Ray& ray, const Hit& hit, SurfacePoint& s) {
  uint32_t i0 = m.indices[3 * hit.triangle], i1 = m.indices[3 * hit.triangle + 1],
           i2 = m.indices[3 * hit.triangle + 2];
  // A deforming mesh: its triangle where the ray found it. The static one is read in place:
  // vertexAt's copies went through the stack (callgrind, Cornell box).
  Vec3 deformed[3];
  const Vec3 *v0 = &deformed[0], *v1 = &deformed[1], *v2 = &deformed[2];
  if (m.positionSteps.empty()) {
    v0 = &m.positions[i0], v1 = &m.positions[i1], v2 = &m.positions[i2];
  } else {
    deformed[0] = deformedVertexAt(m, i0, ray.time);
    deformed[1] = deformedVertexAt(m, i1, ray.time);
    deformed[2] = deformedVertexAt(m, i2, ray.time);
  }
  // The formula is core/surface_lanes.h's, which the SIMD surface kernel shares.
  const uint32_t corner[3] = {i0, i1, i2};
  const auto normal = [&](int k) -> const Vec3& { return m.normals[corner[k]]; };
  const auto uv = [&](int k) -> const Vec2& { return m.uvs[corner[k]]; };
  meshSurfaceOf(toWorld.m.m, toWorld.inv.m, hit.b1, hit.b2, *v0, *v1, *v2, !m.normals.empty(),
                normal, !m.uvs.empty(), uv, s);
  s.material = hit.material >= 0 ? hit.material : m.material;
}

// Scene::surface of prim placed by toWorld: all of s but frontFace. Inlined into both callers,
// so that the static path keeps meshSurface inline (see there).
[[gnu::always_inline]] inline void placedSurface(const Scene& scene, const Primitive& prim,
                                                 const Transform& toWorld, const Ray& ray,
                                                 const Hit& hit, SurfacePoint& s) {
  if (prim.kind == Primitive::Kind::kShape)
    shapeSurface(prim, toWorld, ray, hit, s);
  else
    meshSurface(scene.meshes[prim.mesh], toWorld, ray, hit, s);
}

// A moving primitive is shaded where the ray found it. Its matrix at the hit's time was
// invertible, or the accelerator would have reported no hit. Out of line, so that the static
// path constructs no Transform (two identity matrices stored per hit; callgrind, Cornell box).
[[gnu::noinline]] void movingSurface(const Scene& scene, const Primitive& prim, const Ray& ray,
                                     const Hit& hit, SurfacePoint& s) {
  Transform moved;
  const Transform* placed = movedPlacementAt(prim, ray.time, moved);
  placedSurface(scene, prim, placed ? *placed : moved, ray, hit, s);
}

// An instance array's instance, placed by the matrix derived from its stored inverse
// (Scene::placement). Out of line, as movingSurface.
[[gnu::noinline]] void arraySurface(const Scene& scene, const Primitive& prim, const Ray& ray,
                                    const Hit& hit, SurfacePoint& s) {
  Transform scratch;
  placedSurface(scene, prim, scene.placement(hit.primitive, hit.instance, scratch), ray, hit, s);
  s.instance = hit.instance;
}

}  // namespace

SurfacePoint Scene::surface(const Ray& ray, const Hit& hit) const {
  const Primitive& prim = primitives[hit.primitive];
  SurfacePoint s;
  s.primitive = hit.primitive;
  s.time = ray.time;
  if (!prim.motion.empty())
    movingSurface(*this, prim, ray, hit, s);
  else if (prim.instances)
    arraySurface(*this, prim, ray, hit, s);
  else
    placedSurface(*this, prim, prim.toWorld, ray, hit, s);
  s.frontFace = dot(ray.d, s.ng) < 0;  // after the stores above retire: no stall measured
  return s;
}

}  // namespace tray

#include "lights/light_set.h"

#include "shapes/sphere.h"

namespace tray {

LightSet::LightSet(const Scene& scene) {
  Bounds3 b = scene.bounds();
  float radius = b.empty() || !b.finite() ? 1.0f : std::max(0.5f * length(b.diagonal()), 1e-3f);
  std::vector<float> power;
  firstLight_.assign(scene.primitives.size(), -1);
  isTriangles_.assign(scene.primitives.size(), false);

  for (size_t i = 0; i < scene.primitives.size(); ++i) {
    const Primitive& prim = scene.primitives[i];
    if (prim.kind == Primitive::Kind::kMesh) {
      const TriangleMesh& mesh = scene.meshes[prim.mesh];
      const Material& m = scene.material(mesh.material);
      // Emitters with an emissive texture are left to BSDF sampling (unbiased, with MIS weight
      // 1): a light sample would see only the factor, not the texture (docs/textures.md).
      if (isBlack(m.emissive) || !isFinite(m.emissive) || m.emissiveTexture.valid()) continue;
      firstLight_[i] = int(refs_.size());
      isTriangles_[i] = true;
      for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        const uint32_t* idx = &mesh.indices[3 * t];
        const Vec3 &a = mesh.positions[idx[0]], &bb = mesh.positions[idx[1]],
                   &c = mesh.positions[idx[2]];
        TriangleLight tl;
        tl.p0 = prim.toWorld.point(a);
        tl.e1 = prim.toWorld.point(bb) - tl.p0;
        tl.e2 = prim.toWorld.point(c) - tl.p0;
        Vec3 cr = cross(tl.e1, tl.e2);
        tl.area = 0.5f * length(cr);
        // The front face as Scene::surface computes it: the local winding normal through the
        // inverse transpose, so a mirroring transform flips it as glTF prescribes.
        Vec3 nw = prim.toWorld.normal(cross(bb - a, c - a));
        tl.n = length(nw) > 0 ? normalize(nw) : Vec3(0, 0, 1);
        tl.Le = m.emissive;
        tl.twoSided = m.doubleSided;
        // Degenerate triangles stay in the index space (lightAt relies on it), with no power.
        refs_.push_back({Kind::kTriangle, uint32_t(triangles_.size())});
        power.push_back(tl.area > 0 && std::isfinite(tl.area) ? tl.power() : 0.0f);
        triangles_.push_back(tl);
      }
    } else {
      const Material& m = scene.material(prim.material);
      auto sphere = std::dynamic_pointer_cast<const Sphere>(prim.shape);
      if (!sphere || isBlack(m.emissive) || !isFinite(m.emissive) || m.emissiveTexture.valid())
        continue;
      SphereLight sl;
      sl.center = prim.toWorld.point(Vec3(0.0f));
      // Analytic spheres are placed by similarity transforms; take the mean axis scale.
      float s = (length(prim.toWorld.vector({1, 0, 0})) + length(prim.toWorld.vector({0, 1, 0})) +
                 length(prim.toWorld.vector({0, 0, 1}))) /
                3.0f;
      sl.radius = sphere->radius() * s;
      sl.Le = m.emissive;
      firstLight_[i] = int(refs_.size());
      refs_.push_back({Kind::kSphere, uint32_t(spheres_.size())});
      power.push_back(sl.power());
      spheres_.push_back(sl);
    }
  }
  for (const Light& l : scene.lights) {
    PunctualLight pl{l, radius};
    refs_.push_back({Kind::kPunctual, uint32_t(punctual_.size())});
    power.push_back(pl.power());
    punctual_.push_back(pl);
  }
  if (!isBlack(scene.environment.background) && isFinite(scene.environment.background)) {
    EnvironmentLight env{scene.environment.background, radius};
    environmentIndex_ = int(refs_.size());
    refs_.push_back({Kind::kEnvironment, 0});
    power.push_back(env.power());
    environment_.push_back(env);
  }
  for (float& p : power)
    if (!std::isfinite(p) || p < 0) p = 0;
  table_ = AliasTable(power);
}

LightSample LightSet::sampleLight(const Ref& r, const Vec3& ref, const Vec3& n, bool transmits,
                                  Vec2 u2) const {
  // One return per kind, so each sample is built in place (no copy through a local).
  switch (r.kind) {
    case Kind::kTriangle:
      return triangles_[r.index].sample(ref, u2);
    case Kind::kSphere:
      return spheres_[r.index].sample(ref, u2);
    case Kind::kPunctual:
      return punctual_[r.index].sample(ref);
    case Kind::kEnvironment:
      return environment_[r.index].sample(n, transmits, u2);
  }
  return {};
}

LightSample LightSet::sample(const Vec3& ref, const Vec3& n, bool transmits, float u1,
                             Vec2 u2) const {
  if (table_.empty()) return {};
  float pmf;
  LightSample s = sampleLight(refs_[table_.sample(u1, pmf)], ref, n, transmits, u2);
  s.pdf *= pmf;
  return s;
}

float LightSet::pdf(int index, const Vec3& ref, const Vec3& p) const {
  if (index < 0 || size_t(index) >= refs_.size()) return 0.0f;
  const Ref& r = refs_[size_t(index)];
  float pmf = table_.pmf(uint32_t(index));
  switch (r.kind) {
    case Kind::kTriangle: {
      const TriangleLight& t = triangles_[r.index];
      Vec3 d = p - ref;
      float dist2 = lengthSquared(d);
      return pmf * t.pdf(dist2, dot(t.n, d) / std::sqrt(dist2));
    }
    case Kind::kSphere:
      return pmf * spheres_[r.index].pdf(ref);
    case Kind::kEnvironment:  // directions, not points: see environmentPdf
    case Kind::kPunctual:
      return 0.0f;
  }
  return 0.0f;
}

float LightSet::environmentPdf(const Vec3& n, bool transmits, const Vec3& wi) const {
  if (environmentIndex_ < 0) return 0.0f;
  return table_.pmf(uint32_t(environmentIndex_)) * environment_.front().pdf(n, transmits, wi);
}

}  // namespace tray

#include "lights/light_set.h"

#include "core/front_face.h"
#include "lights/quad_lights.h"

namespace tray {

namespace {

/// Emissive materials that light sampling can represent. Emitters with an emissive texture are
/// left to BSDF sampling (unbiased, with MIS weight 1): a light sample would see only the
/// factor, not the texture (docs/textures.md).
bool sampledEmitter(const Material& m) {
  return !isBlack(m.emissive) && isFinite(m.emissive) && !m.emissiveTexture.valid();
}

}  // namespace

void LightSet::addPrimitive(const Scene& scene, size_t i, std::vector<float>& power) {
  const Primitive& prim = scene.primitives[i];
  if (prim.kind == Primitive::Kind::kMesh) {
    const TriangleMesh& mesh = scene.meshes[prim.mesh];
    const Material& m = scene.material(mesh.material);
    if (!sampledEmitter(m)) return;
    firstLight_[i] = int(power.size());
    isTriangles_[i] = true;
    // Rectangles (two triangles each) sampled as one where triangles may be sampled by solid
    // angle: the first triangle's light is the rectangle, the second's has no power and hits
    // on it are the first's (lightAt). --triangle-sampling area keeps every triangle.
    std::vector<const MeshRectangle*> rectangleAt(mesh.triangleCount(), nullptr);
    std::vector<MeshRectangle> rectangles;
    if (triangleSampling_ != TriangleSampling::kArea)
      rectangles = findMeshRectangles(mesh, prim.toWorld);
    for (const MeshRectangle& r : rectangles) rectangleAt[r.first] = rectangleAt[r.second] = &r;
    if (!rectangles.empty() && !anyRectangle_) {  // the identity for the lights before
      anyRectangle_ = true;
      for (size_t l = 0; l < power.size(); ++l) merged_.push_back(int(l));
    }
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const uint32_t* idx = &mesh.indices[3 * t];
      const Vec3 &a = mesh.positions[idx[0]], &b = mesh.positions[idx[1]],
                 &c = mesh.positions[idx[2]];
      const Vec3 front = triangleFrontNormal(prim.toWorld, a, b, c);
      const MeshRectangle* r = rectangleAt[t];
      if (r && r->first == t) {
        area_.push_back(AreaLight::rectangle(r->corner, r->ex, r->ey, front, m.emissive,
                                             m.doubleSided, triangleSampling_));
        ++rectangleCount_;
      } else {
        // Degenerate triangles and a rectangle's second stay in the index space (lightAt
        // relies on it), with no power.
        area_.push_back(AreaLight::triangle(prim.toWorld.point(a), prim.toWorld.point(b),
                                            prim.toWorld.point(c), front,
                                            r ? Color(0.0f) : m.emissive, m.doubleSided,
                                            triangleSampling_));
      }
      if (anyRectangle_)
        merged_.push_back(r && r->second == t ? firstLight_[i] + int(r->first) : int(power.size()));
      power.push_back(area_.back().power());
      ++triangleCount_;
    }
  } else {
    const Material& m = scene.material(prim.material);
    // Shapes that cannot be sampled (planes, CSG) are left to BSDF sampling.
    if (!sampledEmitter(m) || !(prim.shape->area(prim.toWorld) > 0)) return;
    firstLight_[i] = int(power.size());
    if (anyRectangle_) merged_.push_back(int(power.size()));
    area_.push_back(AreaLight::shape(*prim.shape, prim.toWorld, m.emissive, m.doubleSided));
    power.push_back(area_.back().power());
  }
}

LightSet::LightSet(const Scene& scene, LightSamplerKind kind, TriangleSampling sampling)
    : triangleSampling_(sampling) {
  Bounds3 b = scene.bounds();
  float radius = b.empty() || !b.finite() ? 1.0f : std::max(0.5f * length(b.diagonal()), 1e-3f);
  world_.radius = radius;
  if (!b.empty() && b.finite()) world_.center = 0.5f * (b.lo + b.hi);
  std::vector<float> power;
  firstLight_.assign(scene.primitives.size(), -1);
  isTriangles_.assign(scene.primitives.size(), false);
  // The order (area lights by primitive, punctual, environment) and the power formulas fix
  // the alias table, hence which random numbers pick which light.
  for (size_t i = 0; i < scene.primitives.size(); ++i) addPrimitive(scene, i, power);
  for (const PunctualLightDesc& l : scene.lights) {
    punctual_.emplace_back(l, radius);
    delta_.push_back(int(power.size()));
    power.push_back(punctual_.back().power());
  }
  const Environment& env = scene.environment;
  const Color& bg = env.background;
  if (env.map) {  // an image replaces the constant background
    if (env.intensity > 0 && std::isfinite(env.intensity)) {
      imageEnvironment_.emplace_back(env.map, env.rotation, env.intensity, radius,
                                     env.uniformSampling);
      infinite_.push_back(int(power.size()));
      power.push_back(imageEnvironment_.back().power());
    }
  } else if (!isBlack(bg) && isFinite(bg)) {
    environment_.emplace_back(bg, radius);
    constantEnvironment_ = int(power.size());
    infinite_.push_back(int(power.size()));
    power.push_back(environment_.back().power());
  }
  for (const AreaLight& l : area_) lights_.push_back(&l);
  for (const PunctualLight& l : punctual_) lights_.push_back(&l);
  for (const EnvironmentLight& l : environment_) lights_.push_back(&l);
  for (const ImageEnvironmentLight& l : imageEnvironment_) lights_.push_back(&l);
  std::vector<LightBounds> bounds;
  for (float& p : power) {
    if (!std::isfinite(p) || p < 0) p = 0;
    anyPower_ = anyPower_ || p > 0;
  }
  if (kind == LightSamplerKind::kBvh)
    for (const Light* l : lights_) bounds.push_back(l->bounds());
  chooser_ = makeLightSampler(kind, power, bounds);
  bvh_ = dynamic_cast<const BvhLightSampler*>(chooser_.get());
  if (bvh_ && infinite_.size() == 1 && bvh_->soleInfinite() == infinite_[0])
    escapeLight_ = infinite_[0];
}

LightSample LightSet::sampleOther(int i, const LightSampleContext& ctx, Vec2 u) const {
  // The constant environment through its final class: its sample() inline, no virtual call.
  return i == constantEnvironment_ ? environment_[0].sample(ctx, u)
                                   : lights_[size_t(i)]->sample(ctx, u);
}

float LightSet::pdfOther(int i, const LightSampleContext& ctx, const Vec3& wi, const Vec3& p,
                         const Vec3& n) const {
  return i == constantEnvironment_ ? environment_[0].pdf(ctx, wi, p, n)
                                   : lights_[size_t(i)]->pdf(ctx, wi, p, n);
}

}  // namespace tray

#pragma once
// Scenes of the stability suite (docs/stability.md), built in code. Shared by the tests in
// tests/stability/ and by bench/stability_images.cpp, which renders the documentation images,
// so the pictures show exactly what the tests measure.
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "accel/registry.h"
#include "core/integrator.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "tests/integrators/path_under_test.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray::stability {

using namespace tray::test;

// --- 1. Self-intersection at every scale ---------------------------------------------------

/// A lit floor (analytic plane or a two-triangle mesh) with a unit sphere resting on it, the
/// whole scene scaled by `scale` and moved by `offset`. The point light's intensity grows with
/// scale^2 so irradiance, and therefore every pixel, is the same at every scale.
struct SceneWithCamera {
  Scene scene;
  CameraDesc camera;
};

inline SceneWithCamera acneScene(float scale, const Vec3& offset, bool meshFloor) {
  SceneWithCamera a;
  Scene& s = a.scene;
  const int mat = addMaterial(s, diffuse(Color(0.8f)));
  const Mat4 place = Mat4::translate(offset) * Mat4::scale(Vec3(scale));
  if (meshFloor)
    addMeshInstance(s, addMesh(s, quadMesh(4.0f, mat)), place);
  else
    addShape(s, std::make_shared<Plane>(), place, mat);
  addShape(s, std::make_shared<Sphere>(1.0f),
           Mat4::translate(offset + scale * Vec3(0, 1, 0)) * Mat4::scale(Vec3(scale)), mat);
  s.lights.push_back(pointLight(offset + scale * Vec3(2, 5, 1), Color(30.0f * scale * scale)));
  s.finalize();
  a.camera = lookAt(offset + scale * Vec3(0, 4, 6), offset, 0.9f);
  return a;
}

/// Pixels that show a surface (alpha > 0) but receive (almost) no light: the sphere's own
/// shadow side and its cast shadow, plus any acne.
inline size_t shadowedPixels(const Film& f) {
  size_t dark = 0;
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x) {
      const float* p = f.pixel(Film::kBeauty, x, y);
      if (p[3] > 0 && p[0] < 0.02f) ++dark;
    }
  return dark;
}

/// The textbook mistake, for contrast: direct Lambert lighting from point lights with the
/// shadow ray starting a FIXED distance `epsilon` off the surface (0: on the surface). Right
/// at one scene scale, wrong at others: too small for large coordinates (acne), too large for
/// tiny scenes (light leaks).
class FixedEpsilonDirect final : public Integrator {
 public:
  FixedEpsilonDirect(const RenderContext& ctx, float epsilon)
      : Integrator(ctx), epsilon_(epsilon) {}
  Color Li(const Ray& ray, Sampler&, RayStats& stats, PrimaryHit* primary) const override {
    const Scene& scene = ctx_.scene;
    Hit hit;
    if (!ctx_.accel.intersect(ray, hit)) return scene.environment.background;
    const SurfacePoint s = scene.surface(ray, hit);
    if (primary) primary->hit = true;
    const Vec3 n = s.frontFace ? s.n : -s.n;
    const Color albedo = scene.material(s.material).baseColor;
    Color L(0.0f);
    for (const PunctualLightDesc& light : scene.lights) {
      const Vec3 toLight = light.position - s.p;
      const float dist2 = lengthSquared(toLight);
      const Vec3 wi = toLight / std::sqrt(dist2);
      const float cosI = dot(wi, n);
      if (cosI <= 0) continue;
      const Vec3 o = s.p + epsilon_ * n;
      ++stats.shadowRays;
      if (ctx_.accel.occluded(Ray{o, light.position - o, 0.0f, 1.0f - 1e-4f})) continue;
      L += albedo * (1.0f / kPi) * light.intensity * (cosI / dist2);
    }
    return L;
  }

 private:
  float epsilon_;
};

inline Film renderFixedEpsilon(const SceneWithCamera& a, int w, int h, float epsilon) {
  const PreparedScene prepared(a.scene, a.camera, {w, h});
  const RenderContext ctx = prepared.context(RenderSettings{});
  FixedEpsilonDirect integrator(ctx, epsilon);
  Film film(w, h);
  renderImage(integrator, film);
  return film;
}

// --- 2. Watertightness: a finely tessellated sphere ----------------------------------------

/// A geodesic sphere of radius 1: an icosahedron subdivided `levels` times, vertices pushed onto
/// the sphere and shared between triangles (indexed), outward counter-clockwise winding. Every
/// edge is shared by exactly two triangles and the solid is convex.
inline TriangleMesh geodesicSphere(int levels, int material) {
  const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
  TriangleMesh m;
  m.material = material;
  for (Vec3 v : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t),
                 Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1), Vec3(t, 0, 1),
                 Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    m.positions.push_back(normalize(v));
  m.indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      auto key = std::minmax(a, b);
      auto it = midpoints.find(key);
      if (it != midpoints.end()) return it->second;
      m.positions.push_back(normalize(m.positions[a] + m.positions[b]));
      const uint32_t i = uint32_t(m.positions.size() - 1);
      midpoints.emplace(key, i);
      return i;
    };
    std::vector<uint32_t> next;
    for (size_t f = 0; f + 2 < m.indices.size(); f += 3) {
      const uint32_t a = m.indices[f], b = m.indices[f + 1], c = m.indices[f + 2];
      const uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    m.indices = std::move(next);
  }
  return m;
}

// --- 3. Light trapped by total internal reflection ------------------------------------------

/// A smooth glass material for the path tracer (and Whitted: kt = 1).
inline Material glass(float ior = 1.5f) {
  Material m = diffuse(Color(0.0f));
  m.baseColor = Color(1.0f);
  m.metallic = 0, m.roughness = 0, m.transmission = 1, m.ior = ior;
  m.phong.transmittance = 1.0f;
  return m;
}

/// The camera inside a glass sphere of radius 1 (IOR 1.5), 0.8 from its centre, looking along
/// the sphere's tangent. A ray's distance b from the centre line (its impact parameter) is the
/// same on every chord of a sphere, so rays with b > 1 / 1.5 meet the surface beyond the
/// critical angle every time: trapped by total internal reflection forever, a whispering
/// gallery (the image's dark middle). Wider rays escape to a white sky or see a diffuse ball
/// outside. A small diffuse ball at the centre is never seen by trapped rays (b > 0.3).
inline SceneWithCamera trappedLightScene() {
  SceneWithCamera a;
  Scene& s = a.scene;
  addSphere(s, {0, 0, 0}, 1.0f, addMaterial(s, glass()));
  addSphere(s, {0, 0, 0}, 0.3f, addMaterial(s, diffuse(Color(0.8f, 0.5f, 0.3f))));
  addSphere(s, {3, 0, 2}, 1.0f, addMaterial(s, diffuse(Color(0.3f, 0.5f, 0.8f))));
  s.environment.background = Color(1.0f);
  s.finalize();
  a.camera = lookAt({0, 0, 0.8f}, {1, 0, 0.8f}, 1.6f);
  return a;
}

// --- 4. Caustics: a glass ball focusing a small bright light onto a diffuse floor -----------

/// The path tracer as the stability tests and their images run it: jittered camera rays and
/// independent numbers unless asked, since the failures shown are those of plain Monte Carlo.
inline RenderSettings pathSettings(int spp, float clampIndirect = 0,
                                   const std::string& sampler = "independent") {
  RenderSettings s;
  s.set("integrator", test::pathUnderTest());
  s.set("sampler", sampler);
  s.set("pixel-sampler", "jitter");
  s.set("spp", spp);
  s.set("clamp-indirect", clampIndirect);
  return s;
}

inline SceneWithCamera causticScene() {
  SceneWithCamera a;
  Scene& s = a.scene;
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), addMaterial(s, diffuse(Color(0.8f))));
  addSphere(s, {0, 0.9f, 0}, 0.5f, addMaterial(s, glass()));
  Material lamp = diffuse(Color(0.0f));
  lamp.emissive = Color(400.0f);
  addSphere(s, {0.6f, 4.0f, 0.2f}, 0.08f, addMaterial(s, lamp));
  s.finalize();
  a.camera = lookAt({0, 2.2f, 3.2f}, {0, 0.3f, 0}, 0.75f);
  return a;
}

// --- 7. Degenerate meshes: a smooth sphere mesh on a floor -----------------------------------

/// A geodesic sphere (radius 1) with its exact per-vertex normals.
inline TriangleMesh smoothSphere() {
  TriangleMesh m = geodesicSphere(2, 0);
  m.normals = m.positions;
  return m;
}

/// Sets every 5th vertex normal to NaN; returns how many.
inline size_t poisonNormals(TriangleMesh& m) {
  size_t n = 0;
  for (size_t i = 0; i < m.normals.size(); i += 5, ++n)
    m.normals[i] = Vec3(std::numeric_limits<float>::quiet_NaN());
  return n;
}

/// The mesh on a diffuse floor, lit by a point light and a dim sky, and the camera on it.
inline SceneWithCamera meshOnFloor(TriangleMesh sphere) {
  SceneWithCamera a;
  Scene& s = a.scene;
  const int mat = addMaterial(s, diffuse(Color(0.7f, 0.6f, 0.5f)));
  sphere.material = mat;
  addMeshInstance(s, addMesh(s, std::move(sphere)), Mat4::identity());
  addMeshInstance(s, addMesh(s, quadMesh(3.0f, mat)), Mat4::translate({0, -1, 0}));
  s.lights.push_back(pointLight({2, 4, 3}, Color(40.0f)));
  s.environment.background = Color(0.2f);
  s.environment.ambient = Color(0.2f);
  s.finalize();
  a.camera = lookAt({0, 0.5f, 4}, {0, 0, 0}, 0.8f);
  return a;
}

// --- 8. A white furnace seen by one pixel ----------------------------------------------------

/// A diffuse sphere of albedo `albedo` in a uniform environment of radiance 1: a convex body
/// that sees only the environment reflects exactly albedo x 1. The narrow camera puts the whole
/// pixel on the sphere.
inline SceneWithCamera furnaceScene(float albedo) {
  SceneWithCamera a;
  addSphere(a.scene, {0, 0, 0}, 1.0f, addMaterial(a.scene, diffuse(Color(albedo))));
  a.scene.environment.background = Color(1.0f);
  a.scene.finalize();
  a.camera = lookAt({0, 0, 3}, {0, 0, 0}, 0.05f);
  return a;
}

}  // namespace tray::stability

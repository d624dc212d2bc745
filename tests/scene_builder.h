#pragma once
// Tiny scenes built in code for tests: no files needed.
#include <cmath>
#include <memory>
#include <random>

#include "core/scene.h"
#include "shapes/box.h"
#include "shapes/plane.h"
#include "shapes/sphere.h"

namespace tray::test {

inline int addMaterial(Scene& s, Material m) {
  s.materials.push_back(std::move(m));
  return int(s.materials.size()) - 1;
}

/// A diffuse Phong material (kd only) that is also a Lambert PBR material of the same albedo.
inline Material diffuse(const Color& albedo) {
  Material m;
  m.baseColor = albedo;
  m.metallic = 0;
  m.roughness = 1;
  m.phong.ambient = Color(0.0f);
  m.phong.diffuse = albedo;
  m.phong.specular = Color(0.0f);
  m.hasPhong = true;
  return m;
}

inline uint32_t addShape(Scene& s, std::shared_ptr<const Shape> shape, const Mat4& toWorld,
                         int material) {
  Primitive p;
  p.kind = Primitive::Kind::kShape;
  p.shape = std::move(shape);
  p.toWorld = Transform(toWorld);
  p.material = material;
  p.objectId = int(s.primitives.size());
  p.name = "shape" + std::to_string(s.primitives.size());
  s.primitives.push_back(p);
  return uint32_t(s.primitives.size() - 1);
}

inline uint32_t addSphere(Scene& s, const Vec3& center, float radius, int material) {
  return addShape(s, std::make_shared<Sphere>(radius), Mat4::translate(center), material);
}

/// Adds a mesh (once) and returns its index.
inline uint32_t addMesh(Scene& s, TriangleMesh mesh) {
  s.meshes.push_back(std::move(mesh));
  return uint32_t(s.meshes.size() - 1);
}

/// Places mesh `mesh` with a transform.
inline uint32_t addMeshInstance(Scene& s, uint32_t mesh, const Mat4& toWorld) {
  Primitive p;
  p.kind = Primitive::Kind::kMesh;
  p.mesh = mesh;
  p.toWorld = Transform(toWorld);
  p.objectId = int(s.primitives.size());
  p.name = "mesh" + std::to_string(s.primitives.size());
  s.primitives.push_back(p);
  return uint32_t(s.primitives.size() - 1);
}

/// A square [-h, h]^2 in the y = 0 plane facing +Y, as two triangles.
inline TriangleMesh quadMesh(float h, int material) {
  TriangleMesh m;
  m.positions = {{-h, 0, -h}, {-h, 0, h}, {h, 0, h}, {h, 0, -h}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = material;
  return m;
}

/// A camera at `eye` looking at `target` (+Y up), vertical fov in radians.
inline CameraDesc lookAt(const Vec3& eye, const Vec3& target, float yfov = 0.8f) {
  CameraDesc d;
  d.yfov = yfov;
  Vec3 back = normalize(eye - target);
  Vec3 right = normalize(cross(Vec3(0, 1, 0), back));
  if (!isFinite(right) || length(right) < 1e-6f) right = Vec3(1, 0, 0);
  Vec3 up = cross(back, right);
  Mat4 m;
  for (int i = 0; i < 3; ++i) {
    m.m[i][0] = right[i];
    m.m[i][1] = up[i];
    m.m[i][2] = back[i];
    m.m[i][3] = eye[i];
  }
  d.toWorld = Transform(m);
  return d;
}

/// A random invertible placement: rotation, non-uniform scale and shear, translation of either
/// sign (the SIMD kernels' tests: Transform::vector's 0 * m[r][3] term is -0 for a negative one).
inline Transform randomPlacement(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (;;) {
    Mat4 m;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) m.m[r][c] = (c == 3 ? 10.0f : 1.0f) * u(rng);
    const float det = m.m[0][0] * (m.m[1][1] * m.m[2][2] - m.m[1][2] * m.m[2][1]) -
                      m.m[0][1] * (m.m[1][0] * m.m[2][2] - m.m[1][2] * m.m[2][0]) +
                      m.m[0][2] * (m.m[1][0] * m.m[2][1] - m.m[1][1] * m.m[2][0]);
    if (std::abs(det) > 0.05f) return Transform(m);
  }
}

inline PunctualLightDesc pointLight(const Vec3& p, const Color& intensity) {
  PunctualLightDesc l;
  l.type = PunctualLightDesc::Type::kPoint;
  l.position = p;
  l.intensity = intensity;
  return l;
}

inline PunctualLightDesc spotLight(const Vec3& p, const Vec3& direction, const Color& intensity,
                                   float innerConeAngle, float outerConeAngle) {
  PunctualLightDesc l = pointLight(p, intensity);
  l.type = PunctualLightDesc::Type::kSpot;
  l.direction = normalize(direction);
  l.innerConeAngle = innerConeAngle, l.outerConeAngle = outerConeAngle;
  return l;
}

inline PunctualLightDesc directionalLight(const Vec3& direction, const Color& irradiance) {
  PunctualLightDesc l;
  l.type = PunctualLightDesc::Type::kDirectional;
  l.direction = normalize(direction);
  l.intensity = irradiance;
  return l;
}

/// One light of each KHR_lights_punctual kind: a point, a spot whose cone misses some points
/// of [-3, 3]^3, and a directional light.
inline void addPunctualLights(Scene& scene) {
  scene.lights.push_back(pointLight({1, 3, 1}, Color(20.0f, 15.0f, 10.0f)));
  scene.lights.push_back(spotLight({-1, 4, 0}, {0.2f, -1, 0.1f}, Color(30.0f), 0.2f, 0.6f));
  scene.lights.push_back(directionalLight({0.3f, -1, -0.2f}, Color(2.0f, 2.0f, 1.5f)));
}

}  // namespace tray::test

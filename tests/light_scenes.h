#pragma once
// Scenes where the choice of light or of its sampling matters, built in code, for the
// light-sampler tests, bench/light_sampler_bench.cpp and bench/triangle_sampling_bench.cpp.
#include <cmath>

#include "tests/scene_builder.h"

namespace tray::test {

/// A ground, a box and three spheres lit by a low sun (irradiance 3) beside a constant sky of
/// radiance 1 (the "one directional light plus a background"): the sun gives as much
/// light as the whole sky to surfaces facing it, yet by power it gets 20% of the light samples (the
/// BVH: up to 51% in front of it, none behind).
inline Scene sunAndSkyScene() {
  Scene s;
  const int ground = addMaterial(s, diffuse(Color(0.5f)));
  const int red = addMaterial(s, diffuse(Color(0.7f, 0.2f, 0.15f)));
  Material glossy = diffuse(Color(0.8f));
  glossy.roughness = 0.3f;
  const int shiny = addMaterial(s, glossy);
  addMeshInstance(s, addMesh(s, quadMesh(6, ground)), Mat4::identity());
  addSphere(s, {-1.2f, 0.6f, 0}, 0.6f, red);
  addSphere(s, {0.3f, 0.45f, 0.9f}, 0.45f, shiny);
  addSphere(s, {1.4f, 0.5f, -0.4f}, 0.5f, ground);
  addShape(s, std::make_shared<Box>(Vec3(-0.4f, 0, -0.4f), Vec3(0.4f, 1.2f, 0.4f)),
           Mat4::translate({0.1f, 0, -1.4f}), red);
  PunctualLightDesc sun;
  sun.type = PunctualLightDesc::Type::kDirectional;
  sun.direction = normalize(Vec3(0.8f, -0.45f, 0.5f));  // travelling: a low sun
  sun.intensity = Color(3.2f, 3.0f, 2.7f);
  s.lights.push_back(sun);
  s.environment.background = Color(0.8f, 0.95f, 1.2f);
  s.cameras.push_back(lookAt({0.5f, 3.2f, 5.0f}, {0, 0.3f, 0}, 0.75f));
  s.finalize();
  return s;
}

/// A ground under a 16 x 16 grid of small emissive triangles of varied colour and height, two
/// emissive spheres, two point lights and a spot, with occluders between: at any point a few
/// nearby lights matter and hundreds do not. quadLamps: each lamp a rectangle 0.24 x 0.08 of two
/// triangles instead (spherical rectangles, lights/quad_lights.h).
inline Scene manyLightsScene(bool quadLamps = false) {
  Scene s;
  const int ground = addMaterial(s, diffuse(Color(0.6f)));
  const int grey = addMaterial(s, diffuse(Color(0.4f, 0.45f, 0.5f)));
  addMeshInstance(s, addMesh(s, quadMesh(5, ground)), Mat4::identity());
  TriangleMesh lamps;
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const float x = -4.2f + 0.56f * float(i), z = -4.2f + 0.56f * float(j);
      const float y = 0.25f + 0.6f * float((i * 7 + j * 3) % 5) / 4.0f;
      const uint32_t k = uint32_t(lamps.positions.size());
      // Counter-clockwise seen from below: each lamp faces down.
      lamps.positions.insert(lamps.positions.end(),
                             {{x, y, z}, {x + 0.08f, y, z}, {x, y, z + 0.08f}});
      lamps.indices.insert(lamps.indices.end(), {k, k + 1, k + 2});
      if (!quadLamps) continue;
      // A rectangle 0.24 x 0.08 instead (two triangles sharing their diagonal; issue 37's
      // spherical rectangles): the far corner, and the first corner moved out along x.
      lamps.positions[k + 1].x += 0.16f;
      lamps.positions.push_back({x + 0.24f, y, z + 0.08f});
      lamps.indices.insert(lamps.indices.end(), {k + 2, k + 1, k + 3});
    }
  Material lampMaterial = diffuse(Color(0.0f));
  lampMaterial.emissive = Color(30.0f, 24.0f, 18.0f);
  lamps.material = addMaterial(s, lampMaterial);
  addMeshInstance(s, addMesh(s, std::move(lamps)), Mat4::identity());
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(2.0f, 4.0f, 8.0f);
  addSphere(s, {-2.5f, 0.3f, 2.5f}, 0.12f, addMaterial(s, glow));
  addSphere(s, {2.5f, 0.3f, -2.5f}, 0.12f, addMaterial(s, glow));
  for (int k = 0; k < 5; ++k)
    addSphere(s, {-3.0f + 1.5f * float(k), 0.35f, 0.2f * float(k % 2)}, 0.35f, grey);
  addShape(s, std::make_shared<Box>(Vec3(-2, 0, -0.1f), Vec3(2, 0.6f, 0.1f)),
           Mat4::translate({0, 0, -1.5f}), grey);
  s.lights.push_back(pointLight({3.5f, 1.0f, 3.5f}, Color(1.5f, 1.2f, 1.0f)));
  s.lights.push_back(pointLight({-3.5f, 0.8f, -3.5f}, Color(1.0f, 1.2f, 1.5f)));
  PunctualLightDesc spot = pointLight({0, 2.5f, 2.0f}, Color(6.0f));
  spot.type = PunctualLightDesc::Type::kSpot;
  spot.direction = normalize(Vec3(0, -1, -0.3f));
  spot.innerConeAngle = 0.2f;
  spot.outerConeAngle = 0.4f;
  s.lights.push_back(spot);
  s.cameras.push_back(lookAt({0, 5.5f, 6.5f}, {0, 0, 0.3f}, 0.8f));
  s.finalize();
  return s;
}

/// A large emissive panel (2 x 0.8, two triangles, facing down) against a wall, 1.2 above a
/// floor, a sphere below it: the wall's top and the floor under the panel see it at short range
/// and grazing angles, where sampling its area is noisy (issue 37).
inline Scene panelByAWallScene() {
  Scene s;
  const int white = addMaterial(s, diffuse(Color(0.7f)));
  addMeshInstance(s, addMesh(s, quadMesh(3, white)), Mat4::identity());
  TriangleMesh wall;  // z = -1, facing +z
  wall.positions = {{-3, 0, -1}, {3, 0, -1}, {3, 3, -1}, {-3, 3, -1}};
  wall.indices = {0, 1, 2, 0, 2, 3};
  wall.material = white;
  addMeshInstance(s, addMesh(s, std::move(wall)), Mat4::identity());
  Material glow = diffuse(Color(0.5f));
  glow.emissive = Color(4.0f, 3.6f, 3.0f);
  TriangleMesh panel;  // counter-clockwise seen from below
  panel.positions = {{-1, 1.2f, -1}, {-1, 1.2f, -0.2f}, {1, 1.2f, -0.2f}, {1, 1.2f, -1}};
  panel.indices = {0, 2, 1, 0, 3, 2};
  panel.material = addMaterial(s, glow);
  addMeshInstance(s, addMesh(s, std::move(panel)), Mat4::identity());
  addSphere(s, {0.3f, 0.35f, -0.4f}, 0.35f, addMaterial(s, diffuse(Color(0.6f, 0.3f, 0.2f))));
  s.cameras.push_back(lookAt({0.4f, 1.1f, 2.6f}, {0, 0.7f, -0.8f}, 0.9f));
  s.finalize();
  return s;
}

}  // namespace tray::test

#pragma once
// The ray sets of the accelerator benchmarks (bench/accel_bench.cpp, bench/batch_bench.cpp):
// camera rays row by row (coherent), shadow rays from their hits towards a point light, and
// cosine-distributed bounce rays from the same hits (incoherent), made once per scene with
// Embree so every accelerator traces the same rays.
#include <cmath>
#include <random>
#include <vector>

#include "accel/registry.h"
#include "core/camera.h"
#include "core/ray.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "render/render_setup.h"

namespace tray::bench {

/// The rays every accelerator traces: made once per scene (with Embree) so all trace the same.
struct RaySet {
  std::vector<Ray> camera, shadow, bounce;
};

/// `sceneCamera`: camera rays from the scene's own camera (as rendered), else from a framing of
/// its bounds.
inline RaySet makeRays(const Scene& scene, int width, int height, bool sceneCamera = false) {
  RaySet rays;
  CameraDesc desc = sceneCamera ? chooseCamera(scene, -1)
                                : Camera::framing(scene.bounds(), float(width) / float(height));
  auto camera = Camera::create(desc, width, height);
  auto embree = makeAccelerator("embree", scene);
  Bounds3 b = scene.bounds();
  Vec3 light = b.center() + Vec3(0.3f, 1.5f, 0.4f) * length(b.diagonal());
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Ray r = camera->generateRay(x + 0.5f, y + 0.5f);
      rays.camera.push_back(r);
      Hit h;
      if (!embree->intersect(r, h)) continue;
      SurfacePoint sp = scene.surface(r, h);
      Vec3 ng = dot(sp.ng, r.d) < 0 ? sp.ng : -sp.ng;
      rays.shadow.push_back(spawnRayTo(sp.p, ng, light, 0.0f));
      Vec3 t, s;
      orthonormalBasis(ng, t, s);
      float r1 = u(rng), r2 = u(rng), rad = std::sqrt(r1), phi = 2 * kPi * r2;
      Vec3 d = rad * std::cos(phi) * t + rad * std::sin(phi) * s + std::sqrt(1 - r1) * ng;
      rays.bounce.push_back(spawnRay(sp.p, ng, d, 0.0f));
    }
  return rays;
}

}  // namespace tray::bench

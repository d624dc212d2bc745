#pragma once
// What the accelerator tests trace batches and motion against: random rays inside a scene's
// bounds, a pinhole's rays row by row, and a cube and a sphere moving over the shutter (each
// kind of instance motion).
#include <vector>

#include "core/ray.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "tests/scene_builder.h"
#include "tests/shapes/solid_meshes.h"

namespace tray::test {

/// Rays from random points inside the scene's bounds in uniformly random directions (what
/// bounces look like to a wavefront queue: neighbours share nothing); a third of them short
/// (occlusion at a distance). `randomTime`: each at a random shutter time, else at time 0.
inline std::vector<Ray> randomRaysInBounds(const Scene& scene, int count, uint32_t seed,
                                           bool randomTime) {
  const Bounds3 b = scene.bounds();
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    Sampler s(seed, uint32_t(i), 3);
    const Vec3 o = b.lo + Vec3(s.next1D(), s.next1D(), s.next1D()) * b.diagonal();
    Ray r{o, sampleUniformSphere(s.next2D())};
    if (randomTime) r.time = s.next1D();
    if (i % 3 == 0) r.tmax = 0.3f * length(b.diagonal()) * s.next1D();
    rays.push_back(r);
  }
  return rays;
}

/// Camera rays: a pinhole outside the bounds looking at their centre, row by row (neighbours in
/// the batch are neighbours in the image), at random shutter times; odd rows of random length.
inline std::vector<Ray> coherentRays(const Scene& scene, int width, int height) {
  const Bounds3 b = scene.bounds();
  const Vec3 centre = 0.5f * (b.lo + b.hi), eye = centre + Vec3(0.3f, 0.4f, 1.5f) * b.diagonal();
  const Vec3 forward = normalize(centre - eye), right = normalize(cross(forward, {0, 1, 0}));
  const Vec3 up = cross(right, forward);
  std::vector<Ray> rays;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Sampler s(uint32_t(y * width + x), 0, 9);
      const float px = (x + 0.5f) / width - 0.5f, py = 0.5f - (y + 0.5f) / height;
      Ray r{eye, forward + 0.8f * px * right + 0.8f * py * up};
      r.time = s.next1D();
      if (y % 2) r.tmax = 2.5f * s.next1D();  // odd rows end anywhere: some are not blocked
      rays.push_back(r);
    }
  return rays;
}

/// A cube mesh turning and rising over three motion steps and a sphere (user geometry) moving
/// along x and stretching over two.
inline void addMovingCubeAndBall(Scene& s, int cubeMaterial, int ballMaterial) {
  const uint32_t cube =
      addMeshInstance(s, addMesh(s, boxMesh(Vec3(-0.4f), Vec3(0.4f), cubeMaterial)),
                      Mat4::translate({-0.8f, 0.4f, 0}));
  s.primitives[cube].motion = {
      Mat4::translate({-0.8f, 0.4f, 0}),
      Mat4::translate({-0.7f, 0.7f, 0}) * Mat4::rotate(0, 0.3826834f, 0, 0.9238795f),
      Mat4::translate({-0.5f, 1.0f, 0.2f}) * Mat4::rotate(0, 0.7071068f, 0, 0.7071068f)};
  const uint32_t ball = addSphere(s, {0.6f, 0.35f, 0}, 0.35f, ballMaterial);
  s.primitives[ball].motion = {Mat4::translate({0.4f, 0.35f, 0}),
                               Mat4::translate({1.2f, 0.35f, -0.3f}) * Mat4::scale({1, 1.5f, 1})};
}

}  // namespace tray::test

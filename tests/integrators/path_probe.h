#pragma once
// The path integrator over a finished scene, for tests that call Li with rays of their own
// (closed forms at one point): the camera and size only complete the render context.
#include <memory>

#include "accel/registry.h"
#include "render/renderer.h"
#include "integrators/registry.h"
#include "tests/scene_builder.h"
#include "tests/integrators/path_under_test.h"

namespace tray::test {

struct PathProbe {
  PathProbe(const Scene& scene, int maxDepth)
      : accel(makeAccelerator("embree", scene)),
        camera(Camera::create(lookAt({0, 1, 3}, {0, 0, 0}), 4, 4)),
        ctx{scene, *accel, *camera, settingsWithDepth(maxDepth), 4, 4},
        path(makeIntegrator(ctx, pathUnderTest())) {}
  Color Li(const Ray& ray, Sampler& sampler) { return path->Li(ray, sampler, stats, nullptr); }

  std::unique_ptr<Accelerator> accel;
  std::unique_ptr<Camera> camera;
  RenderContext ctx;
  std::unique_ptr<Integrator> path;
  RayStats stats;

 private:
  static RenderSettings settingsWithDepth(int maxDepth) {
    RenderSettings s;
    s.set("max-depth", maxDepth);
    return s;
  }
};

}  // namespace tray::test

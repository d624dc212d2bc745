#pragma once
// The path integrator over a finished scene, for tests that call Li with rays of their own
// (closed forms at one point): the camera and size only complete the render context.
#include <memory>

#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "tests/integrators/path_under_test.h"
#include "tests/scene_builder.h"

namespace tray::test {

struct PathProbe {
  PathProbe(const Scene& scene, int maxDepth)
      : prepared(scene, lookAt({0, 1, 3}, {0, 0, 0}), {4, 4}),
        path(makeIntegrator(prepared.context(settingsWithDepth(maxDepth)), pathUnderTest())) {}
  Color Li(const Ray& ray, Sampler& sampler) { return path->Li(ray, sampler, stats, nullptr); }

  PreparedScene prepared;
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

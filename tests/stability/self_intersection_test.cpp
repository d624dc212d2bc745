// Stability 1: self-intersection ("shadow acne") at every scene scale, path tracer.
// The Whitted integrator has the same check in tests/integrators/whitted_test.cpp.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/stability/stability_scenes.h"
#include "tests/integrators/path_under_test.h"

namespace tray {
namespace {

using namespace tray::stability;

constexpr int kW = 96, kH = 72;

struct Placement {
  const char* name;
  float scale;
  Vec3 offset;
};

const Placement kPlacements[] = {{"scale 1e-3", 1e-3f, Vec3(0.0f)},
                                 {"scale 1e4", 1e4f, Vec3(0.0f)},
                                 {"moved 1e5", 1.0f, Vec3(1e5f, 0, 1e5f)}};

/// Direct lighting only (max depth 2) from a point light, one sample at each pixel centre: the
/// path tracer's image is deterministic, so a shadowed pixel is shadowed, not noisy.
size_t pathShadowedPixels(const Placement& p, bool meshFloor) {
  RenderSettings st;
  st.set("integrator", test::pathUnderTest());
  st.set("max-depth", 2);
  SceneWithCamera a = acneScene(p.scale, p.offset, meshFloor);
  return shadowedPixels(renderFilm(a.scene, a.camera, kW, kH, st));
}

class PathScale : public ::testing::TestWithParam<bool> {};

TEST_P(PathScale, ShadowedPixelsMatchTheUnitSceneAtEveryScale) {
  const bool mesh = GetParam();
  const size_t reference = pathShadowedPixels({"scale 1", 1.0f, Vec3(0.0f)}, mesh);
  ASSERT_GT(reference, 300u);  // the sphere's unlit half and its cast shadow exist
  ASSERT_LT(reference, size_t(kW * kH / 2));
  for (const Placement& p : kPlacements) {
    const size_t n = pathShadowedPixels(p, mesh);
    std::printf("path, %s floor, %s: %zu shadowed pixels (scale 1: %zu)\n",
                mesh ? "mesh" : "plane", p.name, n, reference);
    EXPECT_NEAR(double(n), double(reference), 0.001 * double(reference)) << p.name;
  }
}

INSTANTIATE_TEST_SUITE_P(FloorKinds, PathScale, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "MeshFloor" : "AnalyticPlane"; });

// --- What fails without the fix --------------------------------------------------------------

TEST(SelfIntersection, AFixedEpsilonFailsAtSomeScale) {
  // The same scenes lit by FixedEpsilonDirect: shadow rays start epsilon (fixed, world units)
  // off the surface instead of the scale-aware float offset of core/ray.h. Each epsilon is
  // wrong somewhere, which the path tracer above never is.
  for (float epsilon : {0.0f, 1e-4f}) {
    const size_t reference = shadowedPixels(renderFixedEpsilon(acneScene(1, Vec3(0.0f), false), kW, kH, epsilon));
    size_t worst = 0;
    for (const Placement& p : kPlacements) {
      const size_t n = shadowedPixels(renderFixedEpsilon(acneScene(p.scale, p.offset, false), kW, kH, epsilon));
      std::printf("fixed epsilon %g, %s: %zu shadowed pixels (its scale 1: %zu)\n", epsilon, p.name,
                  n, reference);
      worst = std::max(worst, n > reference ? n - reference : reference - n);
    }
    // Far more than the 0.1% the robust offset keeps to.
    EXPECT_GT(double(worst), 0.05 * double(reference)) << "epsilon " << epsilon;
  }
}

}  // namespace
}  // namespace tray

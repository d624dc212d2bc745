// Stability 3: light trapped by total internal reflection in a glass sphere. Every path ends
// at the maximum depth (or by Russian roulette), no sample is NaN, and the work is bounded:
// rays are counted, not timed, so the bounds are exact and machine-independent.
#include <gtest/gtest.h>

#include <cstdio>

#include "tests/stability/stability_scenes.h"
#include "tests/integrators/path_under_test.h"

namespace tray {
namespace {

using namespace tray::stability;

constexpr int kW = 48, kH = 36;

struct Case {
  const char* integrator;
  int spp;
};

const Case kCases[] = {{"whitted", 1}, {"path", 4}};

bool allFinite(const Film& f) {
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x)
      for (int c = 0; c < 4; ++c)
        if (!std::isfinite(f.pixel(Film::kBeauty, x, y)[c])) return false;
  return true;
}

RenderStats renderTrapped(const Case& c, int maxDepth) {
  RenderSettings st;
  st.set("integrator", test::orPathUnderTest(c.integrator));
  st.set("pixel-sampler", "jitter");
  st.set("spp", c.spp);
  st.set("max-depth", maxDepth);
  const SceneWithCamera a = trappedLightScene();
  RenderStats stats;
  const Film film = renderFilm(a.scene, a.camera, kW, kH, st, &stats);
  EXPECT_TRUE(allFinite(film)) << c.integrator << " depth " << maxDepth;
  EXPECT_EQ(stats.rays.nanSamples, 0u) << c.integrator << " depth " << maxDepth;
  return stats;
}

class TrappedLight : public ::testing::TestWithParam<Case> {};

TEST_P(TrappedLight, EndsAtMaxDepthWithoutNanAndWithBoundedRays) {
  const Case& c = GetParam();
  const bool whitted = std::string(c.integrator) == "whitted";
  const RenderStats shallow = renderTrapped(c, 8), deep = renderTrapped(c, 64);
  const double camera = double(deep.rays.cameraRays);
  ASSERT_EQ(camera, double(kW * kH * c.spp));
  // The bound: Whitted spawns at most one ray per hit here (glass has kr = 0, diffuse kt = 0)
  // and there are no point lights; a path has at most depth - 1 continuation rays and one shadow
  // ray per vertex.
  for (const auto& [depth, s] : {std::pair{8, shallow}, std::pair{64, deep}}) {
    std::printf("%s, max depth %d: %.2f continuation + %.2f shadow rays per camera ray\n",
                c.integrator, depth, s.rays.secondaryRays / camera, s.rays.shadowRays / camera);
    if (whitted) {
      EXPECT_LE(s.rays.secondaryRays, uint64_t(camera) * uint64_t(depth));
      EXPECT_EQ(s.rays.shadowRays, 0u);
    } else {
      EXPECT_LE(s.rays.secondaryRays, uint64_t(camera) * uint64_t(depth - 1));
      EXPECT_LE(s.rays.shadowRays, uint64_t(camera) * uint64_t(depth));
    }
  }
  // The trap is real: raising the cap from 8 to 64 makes a good fraction of the rays bounce
  // further, so it is the cap (or roulette), not the scene, that ends them.
  const double extra = double(deep.rays.secondaryRays - shallow.rays.secondaryRays) / camera;
  std::printf("%s: %.2f more continuation rays per camera ray at depth 64 than at 8\n",
              c.integrator, extra);
  EXPECT_GT(extra, whitted ? 0.2 * 56 : 0.2 * 5);
}

INSTANTIATE_TEST_SUITE_P(Integrators, TrappedLight, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.integrator); });

// --- What fails without the fix --------------------------------------------------------------

TEST(TrappedLight, WhittedTrappedRaysNeverEscapeSoOnlyTheCapEndsThem) {
  // Trapped rays keep their angle of incidence (a sphere's symmetry), so they stay trapped: the
  // rays spent grow linearly with the cap, the same number of extra rays per extra level. A
  // recursion without a cap would not return for them.
  const Case c = kCases[0];
  const double camera = kW * kH;
  const double r64 = double(renderTrapped(c, 64).rays.secondaryRays) / camera;
  const double r256 = double(renderTrapped(c, 256).rays.secondaryRays) / camera;
  // 1000: the largest --max-depth whitted declares (whitted.cpp).
  const double r1000 = double(renderTrapped(c, 1000).rays.secondaryRays) / camera;
  const double low = (r256 - r64) / 192, high = (r1000 - r256) / 744;
  std::printf(
      "whitted: %.1f / %.1f / %.1f rays per camera ray at depth 64 / 256 / 1000: %.4f "
      "and %.4f of the camera rays still trapped per level\n",
      r64, r256, r1000, low, high);
  EXPECT_GT(high, 0.2);
  EXPECT_NEAR(high, low, 0.05 * low);  // float rounding lets a few escape
}

TEST(TrappedLight, PathRouletteBoundsTheWorkEvenWithoutACap) {
  // With the cap effectively off (1000, the largest --max-depth: a path surviving roulette that
  // long has probability below 0.95^995 = 1e-22), Russian roulette still ends every path: its survival
  // probability is at most 0.95 from the fifth segment on, so a path has on average at most
  // 5 + 1 / 0.05 = 25 continuation rays.
  const Case c = kCases[1];
  const RenderStats s = renderTrapped(c, 1000);
  const double perCamera = double(s.rays.secondaryRays) / double(s.rays.cameraRays);
  std::printf("path, no depth cap: %.2f continuation rays per camera ray\n", perCamera);
  EXPECT_LT(perCamera, 25.0);
}

}  // namespace
}  // namespace tray

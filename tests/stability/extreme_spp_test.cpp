// Stability 8: 65536 samples in one pixel. The renderer averages a pixel's samples in double
// (integrators/integrator.cpp); a float running sum would drift once the sum is thousands of
// times larger than one sample, its rounding step growing with it. Checked against analytic
// values: a uniform emitter (every sample is exactly its radiance) and a white furnace (a
// diffuse sphere of albedo a under a uniform sky of radiance 1 reflects exactly a). The float
// counter-example sums the very same samples.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "accel/registry.h"
#include "core/filter.h"
#include "core/pixel_sampler.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "tests/integrators/path_under_test.h"
#include "tests/stability/stability_scenes.h"

namespace tray {
namespace {

using namespace tray::stability;

constexpr int kSpp = 65536;

RenderSettings settings(const char* integrator) {
  RenderSettings st;
  st.set("integrator", test::orPathUnderTest(integrator));
  st.set("pixel-sampler", "jitter");
  st.set("spp", kSpp);
  st.set("seed", 7);
  return st;
}

/// A sphere emitting `radiance`, filling the 1x1 image.
SceneWithCamera uniformEmitter(float radiance) {
  SceneWithCamera a;
  Material lamp = diffuse(Color(0.0f));
  lamp.emissive = Color(radiance);
  addSphere(a.scene, {0, 0, 0}, 1.0f, addMaterial(a.scene, lamp));
  a.scene.finalize();
  a.camera = lookAt({0, 0, 3}, {0, 0, 0}, 0.05f);
  return a;
}

/// The red channel of each of the pixel's samples, traced as Integrator::renderPixel traces
/// them (same sampler streams, same offsets; the box filter weighs each by 1).
std::vector<float> pixelSamples(const SceneWithCamera& a, const RenderSettings& st) {
  const PreparedScene prepared(a.scene, a.camera, {1, 1});
  const RenderContext ctx = prepared.context(st);
  auto integrator = makeIntegrator(ctx);
  const int spp = st.getInt("spp");
  const PixelSampler ps(PixelSampler::parse(st.getString("pixel-sampler"), spp), spp, 0.5f);
  std::vector<float> out;
  RayStats stats;
  for (int i = 0; i < ps.count(); ++i) {
    Sampler sampler(0, uint32_t(i), st.getInt64("seed"));
    const Vec2 d = ps.offset(i, sampler.next2D());
    out.push_back(
        integrator
            ->Li(prepared.camera().generateRay(0.5f + d.x, 0.5f + d.y), sampler, stats, nullptr)
            .x);
  }
  return out;
}

/// The mistake the renderer avoids: a float running sum.
float floatMean(const std::vector<float>& v) {
  float sum = 0;
  for (float x : v) sum += x;
  return sum / float(v.size());
}

float renderedPixel(const SceneWithCamera& a, const RenderSettings& st) {
  return renderFilm(a.scene, a.camera, 1, 1, st).pixel(Film::kBeauty, 0, 0)[0];
}

class ExtremeSpp : public ::testing::TestWithParam<const char*> {};

TEST_P(ExtremeSpp, UniformEmitterMeanIsExact) {
  // 0.1 is not a binary fraction: each float addition to a large sum rounds.
  const float radiance = 0.1f;
  const SceneWithCamera a = uniformEmitter(radiance);
  const RenderSettings st = settings(GetParam());
  const float rendered = renderedPixel(a, st);
  const float naive = floatMean(pixelSamples(a, st));
  std::printf("%s, %d spp: rendered %.9g (relative error %.1e), float running sum %.9g (%.1e)\n",
              GetParam(), kSpp, rendered, std::fabs(rendered - radiance) / radiance, naive,
              std::fabs(naive - radiance) / radiance);
  EXPECT_EQ(rendered, radiance);
  // The counter-example fails by far more than float's resolution.
  EXPECT_GT(std::fabs(naive - radiance) / radiance, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Integrators, ExtremeSpp, ::testing::Values("whitted", "path"),
                         [](const auto& info) { return std::string(info.param); });

TEST(ExtremeSpp, PathFurnaceMeanMatchesTheAlbedo) {
  // Sky sampling and BSDF sampling are both cosine-weighted here, and their MIS weights sum to
  // one, so every sample is the albedo up to float rounding: the mean must be too.
  const float albedo = 0.7f;
  const SceneWithCamera a = furnaceScene(albedo);
  const RenderSettings st = settings("path");
  const std::vector<float> samples = pixelSamples(a, st);
  double spread = 0;
  for (float x : samples) spread = std::max(spread, std::fabs(double(x) - albedo));
  const float rendered = renderedPixel(a, st), naive = floatMean(samples);
  std::printf(
      "furnace, albedo %g, %d spp: samples within %.1e of it; rendered %.7f, float "
      "running sum %.7f (relative error %.1e)\n",
      albedo, kSpp, spread, rendered, naive, std::fabs(naive - albedo) / albedo);
  EXPECT_LT(spread, 1e-5);
  EXPECT_NEAR(rendered, albedo, 1e-6);
  EXPECT_GT(std::fabs(naive - albedo) / albedo, 1e-4);
}

}  // namespace
}  // namespace tray

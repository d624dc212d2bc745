// Light-path AOVs of the path tracer (core/light_paths.h): the seven layers sum to the beauty
// per pixel, each is zero where its light cannot arrive, and a path is filed by the lobe of its
// first scattering.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "film/aov.h"
#include "tests/integrators/path_under_test.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr int kSize = 32;

Material metal(float roughness) {
  Material m;
  m.baseColor = Color(0.9f, 0.7f, 0.5f);
  m.metallic = 1;
  m.roughness = roughness;
  return m;
}

Material glass() {
  Material m;
  m.baseColor = Color(1.0f);
  m.metallic = 0;
  m.roughness = 0;
  m.transmission = 1;
  return m;
}

Material plastic() {  // Lambert under a GGX coat: diffuse and specular at one surface
  Material m = diffuse(Color(0.2f, 0.5f, 0.8f));
  m.roughness = 0.3f;
  return m;
}

/// Every kind of light path: a floor, a plastic, a rough metal and a glass sphere, an emissive
/// sphere seen directly, a point light and a sky.
Scene everyPath(bool withGlass = true, bool withSky = true) {
  Scene s;
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), addMaterial(s, diffuse(Color(0.6f))));
  addSphere(s, {-1.1f, 0.5f, 0}, 0.5f, addMaterial(s, plastic()));
  addSphere(s, {0.0f, 0.5f, 0}, 0.5f, addMaterial(s, metal(0.2f)));
  if (withGlass) addSphere(s, {1.1f, 0.5f, 0}, 0.5f, addMaterial(s, glass()));
  Material lamp = diffuse(Color(0.0f));
  lamp.emissive = Color(4.0f, 3.0f, 2.0f);
  addSphere(s, {0.0f, 1.6f, -0.8f}, 0.25f, addMaterial(s, lamp));
  s.lights.push_back(pointLight({1, 3, 2}, Color(20.0f)));
  if (withSky) s.environment.background = Color(0.3f, 0.4f, 0.6f);
  s.finalize();
  return s;
}

Film render(const Scene& s, const std::string& integrator = "path", int maxDepth = 8) {
  RenderSettings st;
  st.set("integrator", orPathUnderTest(integrator));
  st.set("spp", 16);
  if (integrator == "path") st.set("max-depth", maxDepth);
  return renderFilm(s, lookAt({0, 1.2f, 4}, {0, 0.5f, 0}), kSize, kSize, st, nullptr,
                    AovSet::parse("lightpaths"));
}

Color layerAt(const Film& f, const std::string& name, int x, int y) {
  const int l = f.findLayer(name);
  EXPECT_GE(l, 0) << name;
  const float* p = f.pixel(l, x, y);
  return {p[0], p[1], p[2]};
}

/// The largest channel of a layer over the image.
float peak(const Film& f, const std::string& name) {
  float m = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) m = std::max(m, maxComponent(abs(layerAt(f, name, x, y))));
  return m;
}

TEST(LightPaths, LayersSumToTheBeautyInEveryPixel) {
  const Film f = render(everyPath());
  double worst = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      Color sum(0.0f);
      for (const auto& name : lightPathNames()) sum += layerAt(f, name, x, y);
      const float* beauty = f.pixel(Film::kBeauty, x, y);
      for (int c = 0; c < 3; ++c) {
        // Each contribution is split into shares summing to 1 in float: the layers differ from
        // the beauty only by the rounding of those products and of the sums' order.
        const double err = std::fabs(double(sum[c]) - beauty[c]);
        worst = std::max(worst, err / std::max(1e-3, double(std::fabs(beauty[c]))));
        EXPECT_LE(err, 1e-5 * std::max(1e-3f, std::fabs(beauty[c]))) << x << "," << y;
      }
    }
  std::printf("largest relative difference, sum of layers vs beauty: %.3g\n", worst);
  // Every kind of path shows up in this scene.
  for (const auto& name : lightPathNames()) EXPECT_GT(peak(f, name), 0.0f) << name;
}

TEST(LightPaths, OpaqueSceneHasNoTransmissionAndNoSkyHasNoBackground) {
  const Film f = render(everyPath(/*withGlass=*/false, /*withSky=*/false));
  EXPECT_EQ(peak(f, "transmission"), 0.0f);
  EXPECT_EQ(peak(f, "background"), 0.0f);
  EXPECT_GT(peak(f, "specular_direct"), 0.0f);
}

TEST(LightPaths, MatteSceneIsAllDiffuseAndDirectLightOnlyHasNoIndirect) {
  // Lambert only (roughness 1, metallic 0: no coat): no specular light at all.
  Scene s;
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), addMaterial(s, diffuse(Color(0.6f))));
  addSphere(s, {0, 0.5f, 0}, 0.5f, addMaterial(s, diffuse(Color(0.8f, 0.3f, 0.2f))));
  s.lights.push_back(pointLight({1, 3, 2}, Color(20.0f)));
  s.finalize();
  const Film full = render(s);
  EXPECT_EQ(peak(full, "specular_direct"), 0.0f);
  EXPECT_EQ(peak(full, "specular_indirect"), 0.0f);
  EXPECT_GT(peak(full, "diffuse_indirect"), 0.0f);  // the floor lights the sphere's underside
  // Two segments (camera -> surface -> light): direct light only, equal to the beauty.
  const Film direct = render(s, "path", 2);
  EXPECT_EQ(peak(direct, "diffuse_indirect"), 0.0f);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Color d = layerAt(direct, "diffuse_direct", x, y);
      const float* b = direct.pixel(Film::kBeauty, x, y);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[c], b[c], 1e-6f * std::max(1.0f, b[c]));
    }
}

TEST(LightPaths, MirrorFilesWhatItReflectsAsSpecular) {
  // A perfect mirror filling the view: everything it shows went through a specular scattering
  // first; the sky it reflects is direct light.
  Scene s;
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), addMaterial(s, diffuse(Color(0.6f))));
  addSphere(s, {0, 0.5f, 0}, 0.5f, addMaterial(s, metal(0.0f)));
  s.lights.push_back(pointLight({1, 3, 2}, Color(20.0f)));
  s.environment.background = Color(0.5f);
  s.finalize();
  RenderSettings st;
  st.set("integrator", pathUnderTest());
  st.set("spp", 4);
  // Seen from above, the sphere's centre reflects the sky.
  const Film f = renderFilm(s, lookAt({0, 1.5f, 2}, {0, 0.5f, 0}, 0.05f), 8, 8, st, nullptr,
                            AovSet::parse("lightpaths"));
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      for (const char* zero : {"diffuse_direct", "diffuse_indirect", "transmission", "emission",
                               "background"})
        EXPECT_EQ(maxComponent(layerAt(f, zero, x, y)), 0.0f) << zero;
      EXPECT_GT(maxComponent(layerAt(f, "specular_direct", x, y)), 0.0f);  // the sky
    }
}

TEST(LightPaths, OnlyThePathTracerSplitsItsLight) {
  EXPECT_THROW(render(everyPath(), "whitted"), Error);
  EXPECT_EQ(AovSet::parse("lightpaths").size(), size_t(kLightPathCount));
  EXPECT_FALSE(AovSet::wantsLightPaths(AovSet::parse("all")));  // whitted renders "all"
}

}  // namespace
}  // namespace tray

// Image-based lighting end to end: escaping rays see the map (path and Whitted), a white
// sphere under a map of constant radiance per hemisphere reflects Lambert's closed form, and a
// small very bright sun converges far faster with importance sampling than with uniform
// sphere sampling at equal samples per pixel.
#include <gtest/gtest.h>

#include <cmath>

#include "bench/sky_maps.h"
#include "lights/image_environment_light.h"
#include "tests/integrators/path_probe.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"
#include "tests/integrators/path_under_test.h"

namespace tray {
namespace {

using namespace tray::test;

Color beauty(const Film& f, int x, int y) {
  const float* p = f.pixel(Film::kBeauty, x, y);
  return Color(p[0], p[1], p[2]);
}

TEST(PathEnvironment, EscapingRaysSeeTheMap) {
  Scene s;
  addSphere(s, {0, -50, 0}, 1, addMaterial(s, diffuse(Color(0.5f))));
  s.environment.map = maps::sunSky(64, 32);
  s.environment.rotation = 40;
  s.environment.intensity = 0.5f;
  s.finalize();
  const ImageEnvironmentLight light(s.environment.map, 40, 0.5f, 1);
  PathProbe probe(s, 5);
  for (Vec3 d : {Vec3(0, 1, 0), Vec3(0.3f, 0.2f, -0.9f), Vec3(-0.7f, 0.1f, 0.7f)}) {
    Sampler sampler(0, 0, 1);
    const Color L = probe.Li(Ray{{0, 0, 0}, normalize(d)}, sampler);
    const Color expected = light.Le(normalize(d));
    EXPECT_NEAR(L.x, expected.x, 1e-5f * (1 + expected.x));
    EXPECT_NEAR(L.z, expected.z, 1e-5f * (1 + expected.z));
  }
}

TEST(PathEnvironment, WhittedBackgroundIsTheMap) {
  Scene s;
  addSphere(s, {0, -50, 0}, 1, addMaterial(s, diffuse(Color(0.5f))));
  s.environment.map = maps::hemispheres(64, 32, Color(3.0f, 2.0f, 1.0f), Color(0.1f));
  s.finalize();
  RenderSettings settings;
  settings.set("integrator", "whitted");
  const Film film = renderFilm(s, lookAt({0, 0, 0}, {0, 1, 0.001f}, 0.5f), 4, 4, settings);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_NEAR(beauty(film, x, y).x, 3.0f, 1e-4f);
      EXPECT_NEAR(beauty(film, x, y).z, 1.0f, 1e-4f);
    }
}

TEST(PathEnvironment, WhittedLightsDiffuseSurfacesByTheMapsIrradiance) {
  // A diffuse sphere (albedo 0.5) under radiance L1 above and L2 below, seen from above and
  // from below: Whitted shows albedo x E(n) / pi = albedo x L1 at the top and albedo x L2 at
  // the bottom (E(n) = pi [(L1 + L2) / 2 + (L1 - L2) / 2 n_y], linear in n: bands 0 and 1 of
  // the spherical harmonics hold it exactly). Without the map's light the sphere was black.
  const float L1 = 2.0f, L2 = 0.5f;
  Scene s;
  addSphere(s, {0, 0, 0}, 1, addMaterial(s, diffuse(Color(0.5f))));
  s.environment.map = maps::hemispheres(256, 128, Color(L1), Color(L2));
  s.finalize();
  RenderSettings settings;
  settings.set("integrator", "whitted");
  const Film top = renderFilm(s, lookAt({0, 5, 0.001f}, {0, 0, 0}, 0.02f), 3, 3, settings);
  const Film bottom = renderFilm(s, lookAt({0, -5, 0.001f}, {0, 0, 0}, 0.02f), 3, 3, settings);
  EXPECT_NEAR(beauty(top, 1, 1).x, 0.5f * L1, 0.01f * L1);
  EXPECT_NEAR(beauty(bottom, 1, 1).x, 0.5f * L2, 0.01f * L1);
}

TEST(PathEnvironment, WhiteSphereUnderTwoHemispheresMatchesLambert) {
  // Irradiance of a Lambertian with normal n under radiance L1 above and L2 below:
  // E(n) = pi [(L1 + L2) / 2 + (L1 - L2) / 2 n_y]; albedo 1 reflects L = E / pi. A convex
  // sphere never sees itself, so this is the whole answer.
  const float L1 = 2.0f, L2 = 0.5f;
  Scene s;
  addSphere(s, {0, 0, 0}, 1, addMaterial(s, diffuse(Color(1.0f))));
  s.environment.map = maps::hemispheres(256, 128, Color(L1), Color(L2));
  s.finalize();
  PathProbe probe(s, 4);
  for (Vec3 n : {Vec3(0, 1, 0), Vec3(0.6f, 0.5f, 0.2f), Vec3(1, 0, 0), Vec3(-0.3f, -0.7f, 0.5f),
                 Vec3(0, -1, 0)}) {
    n = normalize(n);
    const float expected = (L1 + L2) / 2 + (L1 - L2) / 2 * n.y;
    double sum = 0;
    const int samples = 16000;
    for (int i = 0; i < samples; ++i) {
      Sampler sampler(0, uint32_t(i), 11);
      sum += probe.Li(Ray{3.0f * n, -n}, sampler).x;
    }
    EXPECT_NEAR(sum / samples, expected, 0.01 * expected) << "n_y " << n.y;
  }
}

double mse(const Film& a, const Film& b) {
  double sum = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const Color d = beauty(a, x, y) - beauty(b, x, y);
      sum += double(dot(d, d)) / 3;
    }
  return sum / (a.width() * a.height());
}

TEST(PathEnvironment, SmallBrightSunConvergesFarFasterThanUniformSampling) {
  // A diffuse floor and sphere under a sky whose 2-degree sun gives most of the light. At 16
  // spp, uniform sphere sampling rarely finds the sun (fireflies); importance sampling does.
  auto scene = [](bool uniform) {
    Scene s;
    const int grey = addMaterial(s, diffuse(Color(0.6f)));
    addShape(s, std::make_shared<Plane>(), Mat4::identity(), grey);
    addSphere(s, {0, 1, 0}, 1, grey);
    s.environment.map = maps::sunSky(256, 128);
    s.environment.uniformSampling = uniform;
    s.finalize();
    return s;
  };
  const Scene importance = scene(false), uniform = scene(true);
  const CameraDesc cam = lookAt({0, 3, 6}, {0, 0.8f, 0}, 0.7f);
  RenderSettings settings;
  settings.set("integrator", test::pathUnderTest());
  settings.set("max-depth", 3);
  settings.set("spp", 1024);
  const Film reference = renderFilm(importance, cam, 12, 12, settings);
  settings.set("spp", 16);
  settings.set("seed", 5);
  const double mseImportance = mse(renderFilm(importance, cam, 12, 12, settings), reference);
  const double mseUniform = mse(renderFilm(uniform, cam, 12, 12, settings), reference);
  EXPECT_GT(mseUniform, 5 * mseImportance)
      << "MSE uniform " << mseUniform << ", importance " << mseImportance;
}

}  // namespace
}  // namespace tray

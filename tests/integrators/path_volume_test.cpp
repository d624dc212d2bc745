// KHR_materials_volume through the path tracer's Li: Beer-Lambert absorption inside a smooth
// glass slab, against the closed form at normal incidence. Each face reflects
// R = ((n - 1) / (n + 1))^2; one pass through thickness d transmits tau = exp(-sigma_a d) with
// sigma_a = -ln(attenuationColor) / attenuationDistance; summing the incoherent multiple
// reflections (a geometric series in R^2 tau^2):
//   T = (1 - R)^2 tau / (1 - R^2 tau^2)     (per channel).
// A lower-priority medium inside the slab is a false interface (path_nested_test.cpp): the
// glass stays the medium in effect and keeps absorbing across it.
#include <gtest/gtest.h>

#include <cmath>

#include "shapes/box.h"
#include "tests/integrators/path_probe.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

Material absorbingGlass(const Color& attenuation, float distance, int priority) {
  Material m;
  m.baseColor = Color(1.0f), m.metallic = 0, m.roughness = 0, m.transmission = 1, m.ior = 1.5f;
  m.priority = priority;
  m.layers.attenuationColor = attenuation;
  m.layers.attenuationDistance = distance;
  return m;
}

double slabTransmittance(double ior, double tau) {
  const double R = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
  return (1 - R) * (1 - R) * tau / (1 - R * R * tau * tau);
}

/// Mean radiance looking straight down through a slab y in [0, 3] of absorbing glass (with,
/// optionally, a non-absorbing lower-priority water slab y in [1, 2] inside it) onto an
/// emitter of radiance 1 facing up.
Color radianceThroughSlab(const Material& glass, bool water, int samples,
                          const TextureImage* texture = nullptr) {
  Scene s;
  if (texture) s.textures.push_back(*texture);
  addShape(s, std::make_shared<Box>(Vec3(-20, 0, -20), Vec3(20, 3, 20)), Mat4::identity(),
           addMaterial(s, glass));
  if (water) {
    Material w = absorbingGlass(Color(1.0f), kInfinity, glass.priority - 1);
    w.ior = 1.33f;
    addShape(s, std::make_shared<Box>(Vec3(-20, 1, -20), Vec3(20, 2, 20)), Mat4::identity(),
             addMaterial(s, w));
  }
  Material emitter = diffuse(Color(0.0f));
  emitter.emissive = Color(1.0f);
  addMeshInstance(s, addMesh(s, quadMesh(50.0f, addMaterial(s, emitter))),
                  Mat4::translate({0, -1, 0}));
  s.finalize();
  PathProbe probe(s, 256);
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < samples; ++i) {
    Sampler sampler(7, uint32_t(i), 11, Sampler::Sequence::kIndependent);
    const Color L = probe.Li(Ray{{0.1234f, 5, 0.0567f}, {0, -1, 0}}, sampler);
    for (int k = 0; k < 3; ++k) sum[k] += L[k];
  }
  return {float(sum[0] / samples), float(sum[1] / samples), float(sum[2] / samples)};
}

constexpr int kSamples = 100000;
// A sample is 0 (reflected away) or tau^k (k odd passes): the standard deviation of the mean
// is below sqrt(T (1 - T) / N) = 1.6e-3 at T ~ 0.5; 4 of them.
constexpr double kTolerance = 6.5e-3;

TEST(PathVolume, BeerLambertThroughAGlassSlab) {
  // attenuationColor at distance 2: over the slab's 3 units tau = colour^(3/2).
  const Color colour(0.5f, 0.8f, 1.0f);
  const Color L = radianceThroughSlab(absorbingGlass(colour, 2.0f, 0), false, kSamples);
  for (int k = 0; k < 3; ++k) {
    const double tau = std::pow(double(colour[k]), 1.5);
    EXPECT_NEAR(L[k], slabTransmittance(1.5, tau), kTolerance) << "channel " << k;
  }
  // Blue is not absorbed: the plain slab (0.923), distinct from red's 0.33.
  EXPECT_GT(L.z - L.x, 0.5f);
}

TEST(PathVolume, FalseInterfacesInsideKeepTheGlassAbsorbing) {
  // The water (priority below the glass) is not in effect anywhere: the path crosses 3 units
  // of glass and two interfaces, as without it.
  const Color colour(0.3f, 0.6f, 0.9f);
  const Color L = radianceThroughSlab(absorbingGlass(colour, 3.0f, 2), true, kSamples);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(L[k], slabTransmittance(1.5, colour[k]), kTolerance) << "channel " << k;
}

TEST(PathVolume, TexturedMetallicBelowAFactorOfOneStillRefracts) {
  // glTF's default metallicFactor 1 with a metallicRoughnessTexture whose blue (metalness) is 0
  // is glass at every point (the Khronos transmission samples are made so): the path enters
  // and leaves it as a medium, with the right relative IOR on the way out and its absorption.
  TextureImage black;
  black.name = "metal 0";
  black.width = black.height = 1;
  black.pixels = {0, 1, 0};
  Material m = absorbingGlass(Color(0.5f, 0.8f, 1.0f), 3.0f, 0);
  m.metallic = 1;
  m.metallicRoughnessTexture.image = 0;
  const Color L = radianceThroughSlab(m, false, kSamples / 4, &black);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(L[k], slabTransmittance(1.5, m.layers.attenuationColor[k]), 2 * kTolerance)
        << "channel " << k;
}

TEST(PathVolume, LightInsideTheGlassIsAbsorbedAlongTheShadowRay) {
  // Index-matched absorbing "glass" (IOR 1: no refraction, no reflection) holds a Lambert
  // floor and a point light. Seen from above, the floor point reflects
  //   albedo / pi x I cos / r^2 x tau(r)  (the shadow segment, inside)  x tau(2)  (the view
  // segment from the top face, y = 2, down to the floor); tau(d) = colour^d at distance 1.
  const Color colour(0.5f, 0.8f, 1.0f);
  Material glass = absorbingGlass(colour, 1.0f, 0);
  glass.ior = 1.0f;
  Scene s;
  addShape(s, std::make_shared<Box>(Vec3(-20, -1, -20), Vec3(20, 2, 20)), Mat4::identity(),
           addMaterial(s, glass));
  addMeshInstance(s, addMesh(s, quadMesh(10.0f, addMaterial(s, diffuse(Color(0.6f))))),
                  Mat4::identity());
  const Vec3 light(0, 1, 0), at(0.5f, 0, 0.25f);
  s.lights.push_back(pointLight(light, Color(5.0f)));
  s.finalize();
  PathProbe probe(s, 3);  // camera -> glass -> floor, and the light sample there
  Sampler sampler(3, 0, 1);
  const Color L = probe.Li(Ray{at + Vec3(0, 5, 0), {0, -1, 0}}, sampler);
  const double r = length(light - at), E = 5.0 * (1.0 / r) / (r * r);
  for (int k = 0; k < 3; ++k) {
    const double expected = 0.6 / kPi * E * std::pow(double(colour[k]), r + 2.0);
    EXPECT_NEAR(L[k], expected, 1e-4 * expected) << "channel " << k;
  }
}

TEST(PathVolume, AbsorptionCoefficientFromTheExtensionFields) {
  MaterialLayers l;
  EXPECT_TRUE(isBlack(l.absorption()));  // the extension's default distance is infinite
  l.attenuationColor = Color(std::exp(-1.0f), 1.0f, 0.0f);
  l.attenuationDistance = 0.5f;
  const Color s = l.absorption();
  EXPECT_NEAR(s.x, 2.0f, 1e-5f);
  EXPECT_EQ(s.y, 0.0f);
  EXPECT_TRUE(std::isfinite(s.z) && s.z > 100.0f);  // black: finite, absorbs everything
}

}  // namespace
}  // namespace tray

// Nested dielectrics with priorities (Schmidt & Budge 2002) traced through the path tracer's
// Li, against the closed form for a stack of smooth, non-absorbing interfaces seen at normal
// incidence. Each real interface reflects R = ((n1 - n2) / (n1 + n2))^2; with incoherent
// multiple reflections between lossless interfaces, R/T adds over the stack (the "pile of
// plates" result: m plates give T = (1 - R) / (1 + (2m - 1) R)), so the light that crosses
// the whole stack is T = 1 / (1 + sum R_i / (1 - R_i)). A false interface (the surface of a
// medium that is not in effect) must add nothing, so the result tells which interfaces the
// medium stack made real.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shapes/box.h"
#include "tests/integrators/path_probe.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

double reflectance(double n1, double n2) { return (n1 - n2) * (n1 - n2) / ((n1 + n2) * (n1 + n2)); }

/// Transmittance of the stack of real interfaces (n_i, n_i+1) along `iors`.
double stackTransmittance(const std::vector<double>& iors) {
  double sum = 0;
  for (size_t i = 0; i + 1 < iors.size(); ++i) {
    const double R = reflectance(iors[i], iors[i + 1]);
    sum += R / (1 - R);
  }
  return 1 / (1 + sum);
}

Material dielectric(float ior, int priority) {
  Material m;
  m.baseColor = Color(1.0f), m.metallic = 0, m.roughness = 0, m.transmission = 1, m.ior = ior;
  m.priority = priority;
  return m;
}

/// Mean radiance seen looking straight down through a glass slab (y in [0, 3], IOR 1.5,
/// priority 2) holding a water slab (y in [1, 2], IOR 1.33, priority `waterPriority`) onto a
/// one-sided emitter of radiance 1 facing up below them; everything else is black.
double radianceThroughStack(int waterPriority, int samples) {
  Scene s;
  addShape(s, std::make_shared<Box>(Vec3(-20, 0, -20), Vec3(20, 3, 20)), Mat4::identity(),
           addMaterial(s, dielectric(1.5f, 2)));
  addShape(s, std::make_shared<Box>(Vec3(-20, 1, -20), Vec3(20, 2, 20)), Mat4::identity(),
           addMaterial(s, dielectric(1.33f, waterPriority)));
  Material emitter = diffuse(Color(0.0f));
  emitter.emissive = Color(1.0f);
  addMeshInstance(s, addMesh(s, quadMesh(50.0f, addMaterial(s, emitter))),
                  Mat4::translate({0, -1, 0}));
  s.finalize();
  PathProbe probe(s, 256);
  double sum = 0;
  for (int i = 0; i < samples; ++i) {
    Sampler sampler(7, uint32_t(i), 11, Sampler::Sequence::kIndependent);
    sum += probe.Li(Ray{{0.1234f, 5, 0.0567f}, {0, -1, 0}}, sampler).x;
  }
  return sum / samples;
}

constexpr int kSamples = 400000;
// Each sample is 0 or about 1 (Russian roulette rescales a few), so the mean's standard
// deviation is about sqrt(T (1 - T) / N) = 4.2e-4; 4 of them.
constexpr double kTolerance = 1.7e-3;

TEST(PathNested, LowerPriorityWaterInsideGlassIsInvisible) {
  // Glass wins inside the overlap: the water's two surfaces are false interfaces, and the
  // stack is air | glass | air. Without priorities it would be 4 interfaces (T = 0.9169).
  const double expected = stackTransmittance({1.0, 1.5, 1.0});  // 0.92308
  EXPECT_NEAR(radianceThroughStack(1, kSamples), expected, kTolerance);
}

TEST(PathNested, HigherPriorityWaterInsideGlassIsAnInterfacePair) {
  const double expected = stackTransmittance({1.0, 1.5, 1.33, 1.5, 1.0});  // 0.91695
  EXPECT_GT(std::fabs(expected - stackTransmittance({1.0, 1.5, 1.0})), 3 * kTolerance);
  EXPECT_NEAR(radianceThroughStack(3, kSamples), expected, kTolerance);
}

}  // namespace
}  // namespace tray

// Rays leaving the lights (Light::sampleLe), for photon mapping and bidirectional path
// tracing, against closed forms: the estimator L |cos| / (pdfPos pdfDir) of every light kind
// averages to the light's emitted power (point 4 pi I, area pi L A per face, a spot's cone
// integral, a directional light's and the environment's flux through the world's disk),
// pdfLe answers for the sampled ray what sampleLe returned, rays from infinite lights cross
// the world sphere, and the EmissionSampler chooses lights in proportion to power. The
// adjoint BSDF is the radiance BSDF with its arguments swapped (Veach 1997, 5.2).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "bench/sky_maps.h"
#include "core/sampler.h"
#include "lights/area_light.h"
#include "lights/emission_sampler.h"
#include "lights/environment_light.h"
#include "lights/image_environment_light.h"
#include "lights/punctual_light.h"
#include "materials/bsdf.h"
#include "shapes/sphere.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

const WorldSphere kWorld{{1, 2, -1}, 3.0f};

/// The mean over n emitted rays of luminance(L) |cos| / (pdfPos pdfDir), checking pdfLe
/// against each sample's densities (the parts that are not deltas) on the way.
double emittedPower(const Light& light, int n, bool checkPdf = true) {
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    Sampler u(3, uint32_t(i), 11);
    const Vec2 u1 = u.next2D(), u2 = u.next2D();
    const LightLeSample s = light.sampleLe(u1, u2, kWorld);
    if (!s.valid()) continue;
    EXPECT_NEAR(length(s.ray.d), 1.0f, 1e-5f);
    const float cosine = isBlack(s.n) ? 1.0f : std::fabs(dot(s.n, s.ray.d));
    sum += double(luminance(s.L)) * cosine / (double(s.pdfPos) * s.pdfDir);
    if (!checkPdf) continue;
    const LightLePdf p = light.pdfLe(s.ray.o, s.n, s.ray.d, kWorld);
    if (p.pos > 0) {
      EXPECT_NEAR(p.pos, s.pdfPos, 1e-5f * s.pdfPos);
    }
    if (p.dir > 0) {
      EXPECT_NEAR(p.dir, s.pdfDir, 1e-4f * s.pdfDir);
    }
    EXPECT_TRUE(p.pos > 0 || p.dir > 0);
  }
  return sum / n;
}

TEST(LightEmission, PointLightEmitsFourPiIntensity) {
  PunctualLightDesc d;
  d.position = {0, 1, 0}, d.intensity = Color(2, 3, 4);
  const PunctualLight light(d, kWorld.radius);
  EXPECT_NEAR(emittedPower(light, 20000), 4 * kPi * luminance(d.intensity), 1e-3);
  EXPECT_NEAR(emittedPower(light, 20000), light.power(), 1e-3);
}

TEST(LightEmission, SpotLightEmitsItsConeIntegral) {
  PunctualLightDesc d;
  d.type = PunctualLightDesc::Type::kSpot;
  d.position = {0, 1, 0}, d.direction = normalize(Vec3(0.3f, -1, 0.2f));
  d.innerConeAngle = 0.2f, d.outerConeAngle = 0.6f;
  const PunctualLight light(d, kWorld.radius);
  // 2 pi I int_{cos outer}^{1} falloff(c) dc, by the midpoint rule.
  const double co = std::cos(0.6), ci = std::cos(0.2);
  double integral = 0;
  const int steps = 100000;
  for (int i = 0; i < steps; ++i) {
    const double c = co + (1 - co) * (i + 0.5) / steps;
    const double t = std::clamp((c - co) / (ci - co), 0.0, 1.0);
    integral += t * t * (1 - co) / steps;
  }
  const double expected = 2 * kPi * integral;
  EXPECT_NEAR(emittedPower(light, 200000), expected, 0.01 * expected);
  // Every ray leaves inside the outer cone.
  for (int i = 0; i < 1000; ++i) {
    Sampler u(1, uint32_t(i), 2);
    const LightLeSample s = light.sampleLe(u.next2D(), u.next2D(), kWorld);
    EXPECT_GE(dot(s.ray.d, d.direction), float(co) - 1e-5f);
  }
}

TEST(LightEmission, DirectionalLightCrossesTheWorldDiskWithItsFlux) {
  PunctualLightDesc d;
  d.type = PunctualLightDesc::Type::kDirectional;
  d.direction = normalize(Vec3(0.2f, -1, 0.4f)), d.intensity = Color(1.5f);
  const PunctualLight light(d, kWorld.radius);
  EXPECT_NEAR(emittedPower(light, 1000), kPi * 9 * 1.5, 1e-3);
  for (int i = 0; i < 1000; ++i) {
    Sampler u(1, uint32_t(i), 2);
    const LightLeSample s = light.sampleLe(u.next2D(), u.next2D(), kWorld);
    EXPECT_NEAR(dot(s.ray.d, d.direction), 1.0f, 1e-6f);
    // The ray starts outside the world sphere and passes within its radius of the centre.
    const Vec3 oc = kWorld.center - s.ray.o;
    const float along = dot(oc, s.ray.d);
    EXPECT_GT(along, 0.0f);
    EXPECT_LE(length(oc - along * s.ray.d), kWorld.radius * (1 + 1e-5f));
  }
}

TEST(LightEmission, TriangleEmitsPiRadianceAreaPerFace) {
  for (bool twoSided : {false, true}) {
    const AreaLight light =
        AreaLight::triangle({0, 0, 0}, {2, 0, 0}, {0, 0, 1}, {0, -1, 0}, Color(3.0f), twoSided);
    const double perFace = kPi * 3.0 * 1.0;
    EXPECT_NEAR(emittedPower(light, 100000), perFace * (twoSided ? 2 : 1), 0.002 * perFace);
    // A one-sided triangle emits only from its front face; pdfLe says 0 behind it.
    if (!twoSided) {
      EXPECT_EQ(light.pdfLe({0.5f, 0, 0.2f}, {0, -1, 0}, {0, 1, 0}, kWorld).dir, 0.0f);
      for (int i = 0; i < 1000; ++i) {
        Sampler u(1, uint32_t(i), 2);
        EXPECT_LT(light.sampleLe(u.next2D(), u.next2D(), kWorld).ray.d.y, 0.0f);
      }
    }
  }
}

TEST(LightEmission, SphereEmitsOutwardWithPiRadianceArea) {
  const Sphere sphere(0.5f);
  const Transform toWorld(Mat4::translate({1, 0, 0}));
  const AreaLight light = AreaLight::shape(sphere, toWorld, Color(2.0f), true);
  const double expected = kPi * 2.0 * 4 * kPi * 0.25;
  EXPECT_NEAR(emittedPower(light, 100000), expected, 0.002 * expected);
  for (int i = 0; i < 1000; ++i) {
    Sampler u(1, uint32_t(i), 2);
    const LightLeSample s = light.sampleLe(u.next2D(), u.next2D(), kWorld);
    EXPECT_GT(dot(s.ray.o - Vec3(1, 0, 0), s.ray.d), 0.0f);  // leaves outward
    EXPECT_NEAR(length(s.ray.o - Vec3(1, 0, 0)), 0.5f, 1e-5f);
  }
}

TEST(LightEmission, EnvironmentsSendTheirFluxThroughTheWorldDisk) {
  const EnvironmentLight constant(Color(0.7f), kWorld.radius);
  EXPECT_NEAR(emittedPower(constant, 1000), 0.7 * 4 * kPi * kPi * 9, 1e-2);
  EXPECT_NEAR(emittedPower(constant, 1000), constant.power(), 1e-2);
  auto map = maps::makeMap(32, 16, "bumpy", [](const Vec3& d) {
    const float a = 1.0f + 0.8f * std::sin(7 * d.x + 3 * d.z) * std::cos(5 * d.y);
    return Color(a, 0.5f * a, 2.0f * a);
  });
  const ImageEnvironmentLight image(map, 30, 1.5f, kWorld.radius);
  const double power = emittedPower(image, 400000, false);
  EXPECT_NEAR(power, image.power(), 0.01 * image.power());
  // pdfLe agrees with the sample's direction density, but for a direction that lands on a
  // cell edge after the uv round trip (rotation's trigonometry): at most 1 in 1000.
  int disagree = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    Sampler u(3, uint32_t(i), 11);
    const Vec2 u1 = u.next2D(), u2 = u.next2D();
    const LightLeSample e = image.sampleLe(u1, u2, kWorld);
    ASSERT_TRUE(e.valid());
    const LightLePdf p = image.pdfLe(e.ray.o, e.n, e.ray.d, kWorld);
    EXPECT_NEAR(p.pos, e.pdfPos, 1e-6f * e.pdfPos);
    disagree += std::fabs(p.dir - e.pdfDir) > 2e-3f * e.pdfDir;
  }
  EXPECT_LE(disagree, n / 1000);
}

TEST(LightEmission, SamplerChoosesLightsByPowerAndEstimatesTheirSum) {
  Scene s;
  Material m = diffuse(Color(0.0f));
  m.emissive = Color(4.0f);
  addSphere(s, {0, 0, 0}, 0.5f, addMaterial(s, m));
  PunctualLightDesc d;
  d.position = {0, 3, 0}, d.intensity = Color(5.0f);
  s.lights.push_back(d);
  s.environment.background = Color(0.1f);
  s.finalize();
  const LightSet lights(s);
  const EmissionSampler emitter(lights);
  double total = 0, sum = 0;
  for (size_t i = 0; i < lights.size(); ++i) total += lights.light(i).power();
  for (size_t i = 0; i < lights.size(); ++i)
    EXPECT_NEAR(emitter.pmf(int(i)), lights.light(i).power() / total, 1e-5);
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    Sampler u(2, uint32_t(i), 9);
    const float ul = u.next1D();
    const Vec2 u1 = u.next2D(), u2 = u.next2D();
    const EmittedRay e = emitter.sample(ul, u1, u2);
    ASSERT_TRUE(e.valid());
    const float cosine = isBlack(e.le.n) ? 1.0f : std::fabs(dot(e.le.n, e.le.ray.d));
    sum += double(luminance(e.le.L)) * cosine / (double(e.pmf) * e.le.pdfPos * e.le.pdfDir);
  }
  EXPECT_NEAR(sum / n, total, 0.01 * total);
}

TEST(AdjointBsdf, IsTheRadianceBsdfWithItsArgumentsSwapped) {
  Material glass;
  glass.metallic = 0, glass.roughness = 0.5f, glass.transmission = 1, glass.ior = 1.5f;
  const Vec3 n(0, 0, 1);
  const float eta = 1.5f;
  const Bsdf front(glass, n, eta), back(glass, -n, 1.0f / eta);
  int transmissions = 0;
  for (int i = 0; i < 2000; ++i) {
    Sampler u(4, uint32_t(i), 1);
    const Vec3 wo = normalize(sampleCosineHemisphere(u.next2D()));
    const Vec3 wi = normalize(sampleUniformSphere(u.next2D()));
    float pdf = 0, pdfSwapped = 0;
    const Color fImportance = front.evalImportance(wo, wi, pdf);
    // f(wi, wo): a BSDF whose normal faces wi (the constructor's convention).
    const Color fSwapped = wi.z > 0 ? front.eval(wi, wo, pdfSwapped) : back.eval(wi, wo, pdfSwapped);
    EXPECT_NEAR(fImportance.x, fSwapped.x, 2e-3f * std::max(1.0f, fSwapped.x)) << i;
    transmissions += wi.z < 0 && fImportance.x > 0;
    // The radiance BSDF differs from it by 1/eta^2 in transmission.
    const Color fRadiance = front.eval(wo, wi, pdf);
    if (wi.z < 0) {
      EXPECT_NEAR(fRadiance.x * eta * eta, fImportance.x, 1e-4f * fImportance.x + 1e-7f);
    }
  }
  EXPECT_GT(transmissions, 200);
  // Sampled importance values agree with evalImportance.
  for (int i = 0; i < 500; ++i) {
    Sampler u(5, uint32_t(i), 1);
    const Vec3 wo = normalize(sampleCosineHemisphere(u.next2D()));
    const BsdfSample s = front.sampleImportance(wo, u.next1D(), u.next2D());
    if (!s.valid()) continue;
    float pdf = 0;
    const Color f = front.evalImportance(wo, s.wi, pdf);
    EXPECT_NEAR(s.f.x, f.x, 1e-3f * std::max(1.0f, f.x));
  }
}

}  // namespace
}  // namespace tray

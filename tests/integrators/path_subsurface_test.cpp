// Subsurface scattering as a random walk in a homogeneous medium (TRAY_materials_scattering,
// docs/subsurface.md), against closed forms:
// - the Henyey-Greenstein phase function integrates to 1, has mean cosine g, and its sampler
//   draws from it (histogram of cosTheta);
// - the hero-channel free flight is unbiased per channel: E[weight of passing tMax] is
//   exp(-sigma_t tMax) in each channel, however unequal the channels;
// - an index-matched (IOR 1) sphere that absorbs and does not scatter (sigma_s 0, so every
//   flight that stops is a dead path) reproduces Beer-Lambert along a diameter;
// - white furnace: a sphere that scatters and absorbs nothing, in an environment of radiance 1,
//   is 1 wherever it is seen (energy conserved), index-matched or behind a glass boundary;
//   with albedo 0.5 it is visibly darker.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/free_flight.h"
#include "materials/henyey_greenstein.h"
#include "tests/integrators/path_probe.h"
#include "tests/integrators/render_job.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

TEST(HenyeyGreenstein, NormalisedWithMeanCosineG) {
  for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
    const int n = 200000;
    double integral = 0, meanCos = 0;
    for (int i = 0; i < n; ++i) {
      const double mu = -1 + 2 * (i + 0.5) / n;
      const double p = henyeyGreenstein(float(mu), g) * 2 * kPi * 2.0 / n;
      integral += p, meanCos += mu * p;
    }
    EXPECT_NEAR(integral, 1.0, 2e-3) << "g " << g;
    EXPECT_NEAR(meanCos, g, 2e-3) << "g " << g;
  }
}

TEST(HenyeyGreenstein, SamplesFollowThePhaseFunction) {
  // Histogram of cosTheta against the phase function's mass per bin (2 pi p dmu), and the
  // returned pdf against the evaluation.
  const float g = 0.6f;
  const Vec3 dIn = normalize(Vec3(0.3f, -0.5f, 0.8f));
  constexpr int kBins = 20, kN = 200000;
  int hist[kBins] = {};
  Sampler sampler(3, 0, 5, Sampler::Sequence::kIndependent);
  for (int i = 0; i < kN; ++i) {
    float pdf;
    const Vec3 d = sampleHenyeyGreenstein(dIn, g, sampler.next2D(), pdf);
    ASSERT_NEAR(length(d), 1.0f, 1e-4f);
    const float c = dot(d, dIn);
    ASSERT_NEAR(pdf, henyeyGreenstein(c, g), 1e-3f * pdf + 1e-5f);
    hist[std::min(int((c + 1) / 2 * kBins), kBins - 1)]++;
  }
  for (int b = 0; b < kBins; ++b) {
    double mass = 0;
    for (int k = 0; k < 100; ++k) {
      const double mu = -1 + 2.0 * (b + (k + 0.5) / 100) / kBins;
      mass += 2 * kPi * henyeyGreenstein(float(mu), g) * (2.0 / kBins / 100);
    }
    const double sd = std::sqrt(mass * (1 - mass) / kN);
    EXPECT_NEAR(double(hist[b]) / kN, mass, 5 * sd + 1e-5) << "bin " << b;
  }
}

TEST(FreeFlight, HeroChannelPassThroughIsUnbiasedPerChannel) {
  const Color sigmaA(0.2f, 1.0f, 3.0f), sigmaS(0.5f, 0.1f, 0.0f);
  const float tMax = 0.8f;
  constexpr int kN = 300000;
  double sum[3] = {0, 0, 0}, scatterSum[3] = {0, 0, 0};
  Sampler sampler(1, 0, 9, Sampler::Sequence::kIndependent);
  for (int i = 0; i < kN; ++i) {
    const Vec2 u = sampler.next2D();
    Color ratios(1.0f);  // a path's first flight
    const FreeFlight f = sampleFreeFlight(sigmaA, sigmaS, tMax, heroChannel(u.x), u.y, ratios);
    for (int k = 0; k < 3; ++k) (f.scattered ? scatterSum : sum)[k] += f.weight[k];
  }
  for (int k = 0; k < 3; ++k) {
    const double sigmaT = sigmaA[k] + sigmaS[k];
    EXPECT_NEAR(sum[k] / kN, std::exp(-sigmaT * tMax), 4e-3) << "channel " << k;
    // The events' weights integrate sigma_s T(t) over [0, tMax]: the single-scattering albedo
    // times the chance of an interaction.
    const double expected = sigmaS[k] / sigmaT * (1 - std::exp(-sigmaT * tMax));
    EXPECT_NEAR(scatterSum[k] / kN, expected, 4e-3) << "channel " << k;
  }
}

TEST(FreeFlight, RatiosCarryThePathPdfAcrossFlights) {
  // Two flights of one path (a medium, then another beyond a surface) with the hero channel
  // kept: the mean weight of passing both is the product of the transmittances, and every
  // weight stays at most 3 / (the hero's share) times f / p: bounded, however long the path.
  const Color sA(0.5f, 2.0f, 0.1f), sS(1.0f, 0.2f, 3.0f), sA2(2.0f, 0.1f, 0.7f);
  constexpr int kN = 300000;
  double sum[3] = {0, 0, 0};
  float peak = 0;
  Sampler sampler(2, 0, 9, Sampler::Sequence::kIndependent);
  for (int i = 0; i < kN; ++i) {
    const Vec3 u = sampler.next3D();
    const int hero = heroChannel(u.x);
    Color ratios(1.0f);
    const FreeFlight a = sampleFreeFlight(sA, sS, 0.4f, hero, u.y, ratios);
    if (a.scattered) continue;
    const FreeFlight b = sampleFreeFlight(sA2, Color(0.0f), 0.7f, hero, u.z, ratios);
    if (b.scattered) continue;
    const Color w = a.weight * b.weight;
    for (int k = 0; k < 3; ++k) sum[k] += w[k], peak = std::max(peak, w[k]);
  }
  for (int k = 0; k < 3; ++k) {
    const double T = std::exp(-(sA[k] + sS[k]) * 0.4 - sA2[k] * 0.7);
    EXPECT_NEAR(sum[k] / kN, T, 4e-3) << "channel " << k;
  }
  EXPECT_LE(peak, 3.0f);
}

Material scatteringGlass(float ior, const Color& sigmaA, const Color& sigmaS, float g) {
  Material m;
  m.baseColor = Color(1.0f), m.metallic = 0, m.roughness = 0, m.transmission = 1, m.ior = ior;
  // KHR_materials_volume: sigma_a = -ln(colour) / distance, here at distance 1.
  m.layers.attenuationColor = {std::exp(-sigmaA.x), std::exp(-sigmaA.y), std::exp(-sigmaA.z)};
  m.layers.attenuationDistance = 1.0f;
  m.layers.scatteringMedium = true;
  m.layers.scattering = sigmaS;
  m.layers.scatterAnisotropy = g;
  return m;
}

/// Mean radiance of rays from (0, 0, 4) through points of the unit sphere's disk (radius
/// `spread`) toward -z: the sphere of `medium` at the origin in an environment of radiance 1.
/// `error`, when given, receives the standard error of each channel's mean.
Color meanRadiance(const Material& medium, float spread, int samples, Color* error = nullptr) {
  Scene s;
  addSphere(s, {0, 0, 0}, 1.0f, addMaterial(s, medium));
  s.environment.background = Color(1.0f);
  s.finalize();
  PathProbe probe(s, 1000);
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  for (int i = 0; i < samples; ++i) {
    Sampler sampler(11, uint32_t(i), 13, Sampler::Sequence::kIndependent);
    const Vec2 u = sampler.next2D();
    const Ray ray{{spread * (2 * u.x - 1), spread * (2 * u.y - 1), 4}, {0, 0, -1}};
    const Color L = probe.Li(ray, sampler);
    for (int k = 0; k < 3; ++k) sum[k] += L[k], sum2[k] += double(L[k]) * L[k];
  }
  Color mean;
  for (int k = 0; k < 3; ++k) {
    mean[k] = float(sum[k] / samples);
    if (error)
      error->operator[](k) = float(std::sqrt((sum2[k] / samples - mean[k] * mean[k]) / samples));
  }
  return mean;
}

TEST(PathSubsurface, IndexMatchedAbsorberIsBeerLambertAlongADiameter) {
  // sigma_s 0: the medium goes through the random walk's free flights, each channel's
  // attenuation coming from the hero-channel weights alone.
  const Color sigmaA(0.1f, 0.6f, 1.5f);
  const Color L = meanRadiance(scatteringGlass(1.0f, sigmaA, Color(0.0f), 0.0f), 0.0f, 200000);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(L[k], std::exp(-2.0 * sigmaA[k]), 0.01) << "channel " << k;
}

TEST(PathSubsurface, WhiteFurnaceConservesEnergy) {
  // Albedo 1, forward scattering, an optical radius of 2 to 6 (walks of tens of events), the
  // channels far apart (the hero channel's weights at work). Within 4.5 standard errors (and
  // the error itself small: 1.5%).
  const Color sigmaS(4.0f, 2.0f, 6.0f);
  for (float ior : {1.0f, 1.5f}) {
    Color error;
    const Color L =
        meanRadiance(scatteringGlass(ior, Color(0.0f), sigmaS, 0.4f), 0.7f, 80000, &error);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LT(error[k], 0.015f) << "ior " << ior << " channel " << k;
      EXPECT_NEAR(L[k], 1.0f, 4.5f * error[k]) << "ior " << ior << " channel " << k;
    }
  }
  // Not 1 whatever the medium: half the light absorbed per event makes it darker.
  const Color dark = meanRadiance(scatteringGlass(1.5f, sigmaS, sigmaS, 0.4f), 0.7f, 10000);
  for (int k = 0; k < 3; ++k) EXPECT_LT(dark[k], 0.5f) << "channel " << k;
}

TEST(PathSubsurface, WavefrontSameAsScalar) {
  // The walk's draws are taken in step's order, those made ahead first: the wavefront's pixels
  // (a Lambert floor in its matte stage, the glass boundary in its delta stage, the walk in
  // scalar code) are the scalar driver's bit for bit, and walks happened (more secondary rays
  // than without the medium's scattering).
  const auto scene = [](bool scatters) {
    Scene s;
    Material m = scatteringGlass(1.4f, Color(0.3f, 0.5f, 1.0f), Color(6, 4, 2), 0.3f);
    m.layers.scatteringMedium = scatters;
    addSphere(s, {0, 0.6f, 0}, 0.6f, addMaterial(s, m));
    addMeshInstance(s, addMesh(s, quadMesh(3.0f, addMaterial(s, diffuse(Color(0.6f))))),
                    Mat4::identity());
    s.environment.background = Color(0.8f);
    s.cameras.push_back(lookAt({0, 1.2f, 3.0f}, {0, 0.5f, 0}, 0.8f));
    s.finalize();
    return s;
  };
  const Scene s = scene(true);
  test::Job job;
  job.spp = 4;
  const test::Render scalar = test::render(s, job);
  job.integrator = "path-wavefront";
  const test::Render wave = test::render(s, job);
  EXPECT_EQ(test::differingValues(scalar.film, wave.film), 0u);
  EXPECT_EQ(scalar.stats.rays.secondaryRays, wave.stats.rays.secondaryRays);
  job.integrator = "path-scalar";
  EXPECT_GT(scalar.stats.rays.secondaryRays,
            2 * test::render(scene(false), job).stats.rays.secondaryRays);
}

}  // namespace
}  // namespace tray

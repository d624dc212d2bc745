// Chiang et al. 2016's hair BSDF (materials/hair_lobe.h, hair_bsdf.h): energy conservation
// without absorption (the white furnace), the sampling weights and pdf, and importance sampling
// against uniform sampling, as pbrt-v4's src/pbrt/bxdfs_test.cpp checks its HairBxDF.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/bsdf.h"
#include "materials/hair_bsdf.h"
#include "materials/hair_lobe.h"

namespace tray {
namespace {

// Radical inverse in base b: low-discrepancy points without a random state.
double radicalInverse(int base, uint64_t i) {
  double inv = 1.0 / base, f = inv, r = 0;
  while (i) {
    r += f * double(i % uint64_t(base));
    i /= uint64_t(base);
    f *= inv;
  }
  return r;
}

Vec3 uniformSphere(double u1, double u2) {
  double z = 1 - 2 * u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * M_PI * u2;
  return {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
}
constexpr double kSpherePdf = 1 / (4 * M_PI);

float average(const Color& c) {
  return (c.x + c.y + c.z) / 3;
}

const float kBetas[] = {0.1f, 0.3f, 0.5f, 0.7f, 0.9f};

// sigma_a = 0: no energy is absorbed, so the reflected and transmitted radiance under uniform
// unit illumination is 1 for any h, roughness and cuticle tilt (the A_p sum to 1; M_p and N_p
// are normalised). pbrt-v4 averages over h and allows 5%; here each h and 2%. Uniform sampling
// of the sphere resolves lobes down to roughness 0.3 with 100k points; the narrower ones
// (roughness 0.1: an azimuthal width of 0.024 rad) are integrated by the BSDF's own sampling
// below, whose distribution the chi-square and pdf tests check.
TEST(Hair, WhiteFurnaceUniformSampling) {
  const Vec3 wo = normalize(Vec3(0.3f, 0.5f, 0.8f));
  for (float betaM : {0.3f, 0.5f, 0.7f, 0.9f})
    for (float betaN : {0.3f, 0.5f, 0.7f, 0.9f})
      for (float h : {-0.8f, 0.0f, 0.5f}) {
        const HairLobe hair(h, 1.55f, Color(0.0f), betaM, betaN, 2.0f);
        const int count = 100000;
        double sum = 0;
        for (int i = 0; i < count; ++i) {
          Vec3 wi = uniformSphere(radicalInverse(2, uint64_t(i)), radicalInverse(3, uint64_t(i)));
          sum += average(hair.evalProjected(wo, wi));
        }
        double avg = sum / (count * kSpherePdf);
        EXPECT_NEAR(avg, 1.0, 0.02) << "beta_m " << betaM << " beta_n " << betaN << " h " << h;
      }
}

// The furnace for every roughness 0.1 to 0.9 by importance sampling: E[f |cos| / pdf] with wi
// drawn by sample(). Without absorption the pdf is f itself (the lobes are chosen by A_p and
// each sampled exactly), so every sample's weight is 1 (pbrt-v4's Hair.SamplingWeights) and the
// estimate is exact; a sample whose pdf underflows (the trimmed logistic's far tail) is lost
// energy, allowed at 0.1%.
TEST(Hair, WhiteFurnaceEveryRoughnessBySampling) {
  for (float betaM : kBetas)
    for (float betaN : kBetas) {
      const int count = 4000;
      double sum = 0;
      for (int i = 0; i < count; ++i) {
        const float h = std::clamp(float(-1 + 2 * radicalInverse(2, uint64_t(i))), -0.999f, 0.999f);
        const HairLobe hair(h, 1.55f, Color(0.0f), betaM, betaN, 2.0f);
        const Vec3 wo =
            uniformSphere(radicalInverse(3, uint64_t(i)), radicalInverse(5, uint64_t(i)));
        BsdfSample s = hair.sample(
            wo, float(radicalInverse(7, uint64_t(i))),
            {float(radicalInverse(11, uint64_t(i))), float(radicalInverse(13, uint64_t(i)))});
        if (!(s.pdf > 0)) continue;
        const double w = average(s.f) / s.pdf;
        EXPECT_NEAR(w, 1.0, 1e-3) << betaM << " " << betaN << " h " << h;
        sum += w;
      }
      EXPECT_NEAR(sum / count, 1.0, 1e-3) << "beta_m " << betaM << " beta_n " << betaN;
    }
}

// The pdf a sample reports is pdf(wo, wi) and integrates to 1 over the sphere, with absorption
// and a cuticle tilt (which make it differ from f).
TEST(Hair, PdfMatchesSamplesAndIntegratesToOne) {
  const Vec3 wo = normalize(Vec3(-0.4f, 0.2f, 0.9f));
  for (float betaM : {0.2f, 0.5f, 0.9f})
    for (float betaN : {0.2f, 0.5f, 0.9f}) {
      const HairLobe hair(0.3f, 1.55f, Color(0.5f, 1.0f, 2.0f), betaM, betaN, 3.0f);
      double integral = 0;
      const int count = 40000;
      for (int i = 0; i < count; ++i) {
        Vec3 wi = uniformSphere(radicalInverse(2, uint64_t(i)), radicalInverse(3, uint64_t(i)));
        integral += hair.pdf(wo, wi) / kSpherePdf;
        BsdfSample s = hair.sample(
            wo, float(radicalInverse(5, uint64_t(i))),
            {float(radicalInverse(7, uint64_t(i))), float(radicalInverse(11, uint64_t(i)))});
        if (i % 16 == 0 && s.pdf > 1e-3f) {
          EXPECT_NEAR(s.pdf, hair.pdf(wo, s.wi), 1e-3f * s.pdf);
        }
      }
      EXPECT_NEAR(integral / count, 1.0, 0.02) << betaM << " " << betaN;
    }
}

// Importance sampling and uniform sampling estimate the same reflected radiance under a
// non-uniform sky L(w) = w.z^2 (pbrt-v4's Hair.SamplingConsistency), with absorption.
TEST(Hair, ImportanceAndUniformSamplingAgree) {
  for (float betaM : {0.2f, 0.5f, 0.8f})
    for (float betaN : {0.2f, 0.5f, 0.8f}) {
      const Vec3 wo = normalize(Vec3(0.2f, -0.6f, 0.5f));
      const int count = 64 * 1024;
      double importance = 0, uniform = 0;
      for (int i = 0; i < count; ++i) {
        const float h = std::clamp(float(-1 + 2 * radicalInverse(2, uint64_t(i))), -0.999f, 0.999f);
        const HairLobe hair(h, 1.55f, Color(0.25f), betaM, betaN, 2.0f);
        const Vec2 u{float(radicalInverse(3, uint64_t(i))), float(radicalInverse(5, uint64_t(i)))};
        BsdfSample s = hair.sample(wo, float(radicalInverse(7, uint64_t(i))), u);
        if (s.pdf > 0) importance += average(s.f) * s.wi.z * s.wi.z / s.pdf;
        Vec3 wi = uniformSphere(u.x, u.y);
        uniform += average(hair.evalProjected(wo, wi)) * wi.z * wi.z / kSpherePdf;
      }
      EXPECT_NEAR(importance / uniform, 1.0, 0.03) << betaM << " " << betaN;
    }
}

// A chi-square test of the sampled directions against the pdf, on a grid of
// (sin theta, phi) cells whose expected counts are integrated from pdf().
TEST(Hair, SampledDirectionsFollowThePdf) {
  const HairLobe hair(-0.4f, 1.55f, Color(0.3f, 0.6f, 1.2f), 0.4f, 0.5f, 2.0f);
  const Vec3 wo = normalize(Vec3(0.5f, 0.3f, 0.8f));
  constexpr int kTheta = 10, kPhi = 20;
  const int samples = 200000;
  std::vector<double> observed(kTheta * kPhi, 0), expected(kTheta * kPhi, 0);
  auto cell = [&](const Vec3& w) {
    // sin theta = w.x is uniform-area in [-1, 1] (Archimedes): equal-area rows.
    int a = std::clamp(int((w.x + 1) / 2 * kTheta), 0, kTheta - 1);
    double phi = std::atan2(w.z, w.y) + M_PI;
    int b = std::clamp(int(phi / (2 * M_PI) * kPhi), 0, kPhi - 1);
    return a * kPhi + b;
  };
  for (int i = 0; i < samples; ++i) {
    BsdfSample s =
        hair.sample(wo, float(radicalInverse(2, uint64_t(i))),
                    {float(radicalInverse(3, uint64_t(i))), float(radicalInverse(5, uint64_t(i)))});
    if (s.pdf > 0) observed[size_t(cell(s.wi))] += 1;
  }
  // Expected: pdf integrated over each cell by a fine midpoint rule (area element
  // d(sin theta) d phi).
  const int sub = 8;
  for (int a = 0; a < kTheta * sub; ++a)
    for (int b = 0; b < kPhi * sub; ++b) {
      double x = -1 + 2 * (a + 0.5) / (kTheta * sub),
             phi = -M_PI + 2 * M_PI * (b + 0.5) / (kPhi * sub);
      double c = std::sqrt(1 - x * x);
      Vec3 w{float(x), float(c * std::cos(phi)), float(c * std::sin(phi))};
      double area = (2.0 / (kTheta * sub)) * (2 * M_PI / (kPhi * sub));
      expected[size_t(cell(w))] += hair.pdf(wo, w) * area * samples;
    }
  double chi2 = 0;
  int dof = 0;
  for (size_t k = 0; k < observed.size(); ++k) {
    if (expected[k] < 5) continue;  // the usual pooling rule: skip sparse cells
    chi2 += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
    ++dof;
  }
  // Quasi-random samples: far below the chi-square 1e-3 quantile (~ dof + 3.1 sqrt(2 dof)).
  EXPECT_LT(chi2, dof + 3.1 * std::sqrt(2.0 * dof)) << "dof " << dof;
}

// Through Bsdf: a TRAY_materials_hair material on a fibre along x with normal z conserves
// energy in world space (eval divides by the cosine to n, the furnace multiplies it back), and
// its samples' pdf is the one eval reports.
TEST(Hair, BsdfFurnaceInWorldSpace) {
  Material m;
  m.hair.enabled = true;
  m.hair.sigmaA = Color(0.0f);
  m.hair.betaM = 0.4f, m.hair.betaN = 0.6f;
  ShadingMaterial sm = ShadingMaterial::of(m, Vec3(0, 0, 1));
  sm.tangent = Vec3(1, 0, 0);
  ASSERT_FALSE(Bsdf::isLambertOnly(sm));
  ASSERT_FALSE(Bsdf::isGgxMixture(sm));
  const Bsdf bsdf(sm, Vec3(0, 0, 1), 1.55f);
  EXPECT_TRUE(bsdf.transmits());
  const Vec3 wo = normalize(Vec3(0.2f, 0.4f, 0.7f));
  double sum = 0;
  const int count = 40000;
  for (int i = 0; i < count; ++i) {
    Vec3 wi = uniformSphere(radicalInverse(2, uint64_t(i)), radicalInverse(3, uint64_t(i)));
    float pdf;
    sum += average(bsdf.eval(wo, wi, pdf)) * std::fabs(wi.z) / kSpherePdf;
    BsdfSample s = bsdf.sample(
        wo, float(radicalInverse(5, uint64_t(i))),
        {float(radicalInverse(7, uint64_t(i))), float(radicalInverse(11, uint64_t(i)))});
    if (i % 64 == 0 && s.pdf > 1e-3f) {
      EXPECT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 2e-3f * s.pdf);
      EXPECT_NEAR(average(s.f) * std::fabs(s.wi.z) / s.pdf, 1.0, 2e-3);
    }
  }
  EXPECT_NEAR(sum / count, 1.0, 0.02);
}

// The model reads h from wo, so it is not reciprocal; importance transport (BDPT's light
// subpaths, SPPM's photons) uses the adjoint f*(wo, wi) = f(wi, wo), with the pdf of sampling wi
// from wo.
TEST(Hair, ImportanceUsesTheAdjoint) {
  Material m;
  m.hair.enabled = true;
  m.hair.sigmaA = Color(0.2f, 0.5f, 1.0f);
  const Vec3 n(0, 0, 1);
  ShadingMaterial sm = ShadingMaterial::of(m, n);
  sm.tangent = Vec3(1, 0, 0);
  const Bsdf bsdf(sm, n, 1.55f);
  bool differs = false;
  for (int i = 1; i < 200; ++i) {
    Vec3 wo = uniformSphere(radicalInverse(2, uint64_t(i)), radicalInverse(3, uint64_t(i)));
    Vec3 wi = uniformSphere(radicalInverse(5, uint64_t(i)), radicalInverse(7, uint64_t(i)));
    if (wo.z < 0) wo.z = -wo.z;
    float pdf, pdfIgnored;
    const Color adj = bsdf.evalImportance(wo, wi, pdf);
    const Color back = bsdf.eval(wi, wo, pdfIgnored);
    EXPECT_NEAR(adj.y, back.y, 1e-5f * (1 + back.y));
    EXPECT_NEAR(pdf, bsdf.pdf(wo, wi), 1e-5f * (1 + pdf));
    const Color fwd = bsdf.eval(wo, wi);
    if (std::fabs(fwd.y - back.y) > 1e-3f * (fwd.y + back.y)) differs = true;
    BsdfSample s = bsdf.sampleImportance(wo, float(radicalInverse(11, uint64_t(i))),
                                         {float(radicalInverse(13, uint64_t(i))), 0.37f});
    if (s.pdf > 0) {
      EXPECT_NEAR(s.f.y, bsdf.eval(s.wi, wo).y, 1e-5f * (1 + s.f.y));
    }
  }
  EXPECT_TRUE(differs) << "the hair model came out reciprocal: the adjoint is then moot";
}

TEST(Hair, AbsorptionFromColourAndMelanin) {
  // Chiang et al.'s inversion: white hair has no absorption, darker colours more.
  EXPECT_EQ(HairLobe::sigmaAFromReflectance(Color(1.0f), 0.3f).x, 0.0f);
  Color a = HairLobe::sigmaAFromReflectance(Color(0.8f, 0.5f, 0.2f), 0.3f);
  EXPECT_LT(a.x, a.y);
  EXPECT_LT(a.y, a.z);
  Color e = HairLobe::sigmaAFromConcentration(1.0f, 0.0f);
  EXPECT_FLOAT_EQ(e.x, 0.419f);
  EXPECT_FLOAT_EQ(e.z, 1.37f);
}

}  // namespace
}  // namespace tray

#include "materials/bsdf.h"

#include <gtest/gtest.h>

#include "tests/materials/chi2.h"

namespace tray {
namespace {

struct Case {
  const char* name;
  float metallic, roughness, transmission, eta;
};

Material materialOf(const Case& c, const Color& base = Color(1.0f)) {
  Material m;
  m.baseColor = base;
  m.metallic = c.metallic, m.roughness = c.roughness, m.transmission = c.transmission;
  m.ior = c.eta;
  return m;
}

Vec3 direction(float thetaDeg, float phi = 0.3f) {
  float t = thetaDeg * kPi / 180;
  return {std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)};
}

// Every lobe and their mixtures; glass seen from outside (eta 1.5) and from inside (1/1.5).
const Case kCases[] = {
    {"Lambert", 0, 1, 0, 1.5f},
    {"RoughMetal", 1, 0.7f, 0, 1.5f},
    {"GlossyMetal", 1, 0.35f, 0, 1.5f},
    {"Plastic", 0, 0.5f, 0, 1.5f},
    {"HalfMetal", 0.5f, 0.6f, 0, 1.5f},
    {"RoughGlassOutside", 0, 0.6f, 1, 1.5f},
    {"RoughGlassInside", 0, 0.6f, 1, 1 / 1.5f},
    {"GlossyGlass", 0, 0.4f, 1, 1.33f},
    {"GlassOverDiffuse", 0, 0.6f, 0.5f, 1.5f},
};
const float kAngles[] = {10, 50, 80};

class BsdfLobes : public ::testing::TestWithParam<Case> {};

TEST_P(BsdfLobes, SamplingMatchesPdfChiSquare) {
  const Case c = GetParam();
  const Bsdf bsdf(materialOf(c), Vec3{0, 0, 1}, c.eta);
  for (float angle : kAngles) {
    Vec3 wo = direction(angle);
    auto sample = [&](Vec2 u, float uc, Vec3& wi) {
      BsdfSample s = bsdf.sampleLocal(wo, uc, u);
      if (!s.valid()) return false;
      EXPECT_FALSE(s.delta);
      wi = s.wi;
      return true;
    };
    auto pdf = [&](const Vec3& wi) { return bsdf.pdfLocal(wo, wi); };
    test::Chi2Result r = test::chi2Test(sample, pdf, 300000, 17 + uint64_t(angle));
    // Sidak-corrected 1% significance over all the chi-square tests of this file.
    const double alpha = 1 - std::pow(0.99, 1.0 / (std::size(kCases) * std::size(kAngles)));
    EXPECT_GT(r.pValue, alpha) << c.name << " theta_o " << angle << ": chi2 " << r.statistic
                               << " dof " << r.dof;
    // The pdf integrates to the probability that a sample is produced at all.
    EXPECT_NEAR(r.pdfIntegral, r.sampledFraction, 0.01) << c.name << " theta_o " << angle;
  }
}

TEST_P(BsdfLobes, SampleAgreesWithEvalAndPdf) {
  const Case c = GetParam();
  const Bsdf bsdf(materialOf(c, Color(0.8f, 0.5f, 0.3f)), Vec3{0, 0, 1}, c.eta);
  for (float angle : kAngles) {
    Vec3 wo = direction(angle);
    for (int i = 0; i < 2000; ++i) {
      float a = (i * 0.618034f) - std::floor(i * 0.618034f);
      float b = (i * 0.754878f) - std::floor(i * 0.754878f);
      float uc = (i * 0.569840f) - std::floor(i * 0.569840f);
      BsdfSample s = bsdf.sampleLocal(wo, uc, {a, b});
      if (!s.valid()) continue;
      Color f = bsdf.evalLocal(wo, s.wi);
      float pdf = bsdf.pdfLocal(wo, s.wi);
      ASSERT_TRUE(isFinite(s.f) && std::isfinite(s.pdf));
      EXPECT_NEAR(s.pdf, pdf, 1e-3f * pdf + 1e-6f) << c.name << " " << angle;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.f[k], f[k], 1e-3f * f[k] + 1e-6f) << c.name;
    }
  }
}

TEST_P(BsdfLobes, WorldSpaceQueriesMatchTheLocalFrame) {
  // The world-space entry points (and next-event estimation's eval-with-pdf) change frame
  // correctly: a tilted shading frame gives the local answers of the rotated directions.
  const Case c = GetParam();
  const Frame frame = Frame::fromNormal(normalize(Vec3(0.3f, -0.5f, 0.8f)));
  const Bsdf bsdf(materialOf(c, Color(0.8f, 0.5f, 0.3f)), frame.n, c.eta);
  for (float angle : kAngles) {
    const Vec3 wo = direction(angle), woWorld = frame.toWorld(wo);
    for (int i = 0; i < 200; ++i) {
      const Vec3 wi = direction(2.0f + i * 0.88f, i * 2.39996f), wiWorld = frame.toWorld(wi);
      float pdf = -1;
      const Color f = bsdf.eval(woWorld, wiWorld, pdf), fLocal = bsdf.evalLocal(wo, wi);
      const float pdfLocal = bsdf.pdfLocal(wo, wi);
      EXPECT_NEAR(pdf, pdfLocal, 1e-3f * pdfLocal + 1e-5f) << c.name;
      EXPECT_NEAR(bsdf.pdf(woWorld, wiWorld), pdfLocal, 1e-3f * pdfLocal + 1e-5f) << c.name;
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(f[k], fLocal[k], 1e-3f * fLocal[k] + 1e-5f) << c.name;
        EXPECT_NEAR(bsdf.eval(woWorld, wiWorld)[k], fLocal[k], 1e-3f * fLocal[k] + 1e-5f);
      }
    }
  }
}

TEST_P(BsdfLobes, ShortPathsGiveTheGeneralPathsBits) {
  // The world-space entry points take short paths (a lone Lambert lobe skips the mixture; a
  // mixture samples a GGX lobe's direction, then evaluates all lobes in one pass sharing the GGX
  // terms): each must give the bits of the general local computation, which the path tracer's
  // images rely on (docs/path-tracing.md, "Per-vertex work cut, same pixels").
  const Case c = GetParam();
  const Frame frame = Frame::fromNormal(normalize(Vec3(0.3f, -0.5f, 0.8f)));
  const Bsdf bsdf(materialOf(c, Color(0.8f, 0.5f, 0.3f)), frame.n, c.eta);
  for (float angle : kAngles) {
    const Vec3 woWorld = frame.toWorld(direction(angle)), wo = frame.toLocal(woWorld);
    for (int i = 0; i < 500; ++i) {
      const float a = (i * 0.618034f) - std::floor(i * 0.618034f);
      const float b = (i * 0.754878f) - std::floor(i * 0.754878f);
      const float uc = (i * 0.569840f) - std::floor(i * 0.569840f);
      const BsdfSample world = bsdf.sample(woWorld, uc, {a, b});
      const BsdfSample local = bsdf.sampleLocal(wo, uc, {a, b});
      ASSERT_EQ(world.valid(), local.valid()) << c.name << " " << angle << " " << i;
      if (!local.valid()) continue;
      EXPECT_EQ(world.pdf, local.pdf) << c.name << " " << angle << " " << i;
      EXPECT_EQ(world.delta, local.delta) << c.name;
      const Vec3 wi = frame.toWorld(local.wi);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(world.f[k], local.f[k]) << c.name << " " << angle << " " << i;
        EXPECT_EQ(world.wi[k], wi[k]) << c.name << " " << angle << " " << i;
      }
      // Next-event estimation's eval-with-pdf toward the sampled direction: the general
      // local eval and pdf of the same local directions, bit for bit.
      if (local.delta) continue;
      float pdf = -1;
      const Color f = bsdf.eval(woWorld, wi, pdf);
      const Vec3 wiLocal = frame.toLocal(wi);
      EXPECT_EQ(pdf, bsdf.pdfLocal(wo, wiLocal)) << c.name << " " << angle << " " << i;
      for (int k = 0; k < 3; ++k) EXPECT_EQ(f[k], bsdf.evalLocal(wo, wiLocal)[k]) << c.name;
    }
  }
}

TEST_P(BsdfLobes, ReflectsAtMostTheEnergyItReceives) {
  // White furnace for one scattering: E[f |cos| / pdf] <= 1 for a white material. Refraction
  // into a denser medium carries 1/eta^2 radiance scaling, so it is measured without it.
  const Case c = GetParam();
  const Bsdf bsdf(materialOf(c), Vec3{0, 0, 1}, c.eta);
  for (float angle : {0.5f, 30.0f, 60.0f, 85.0f}) {
    Vec3 wo = direction(angle);
    double sum = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
      float a = (i + 0.5f) / n, b = (i * 0.618034f) - std::floor(i * 0.618034f);
      float uc = (i * 0.754878f) - std::floor(i * 0.754878f);
      BsdfSample s = bsdf.sampleLocal(wo, uc, {a, b});
      if (s.valid()) sum += s.weight().x / s.etaScale;
    }
    EXPECT_LE(sum / n, 1.01) << c.name << " theta_o " << angle;
    EXPECT_GT(sum / n, 0.3) << c.name << " theta_o " << angle;  // and does not lose most of it
  }
}

INSTANTIATE_TEST_SUITE_P(Materials, BsdfLobes, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Bsdf, LambertAlbedoIsExact) {
  // metallic 0, roughness 1: pure Lambert (the documented glTF mapping), albedo = baseColor.
  Material m;
  m.metallic = 0, m.roughness = 1, m.baseColor = Color(0.7f);
  Bsdf bsdf(m, Vec3{0, 0, 1}, 1.5f);
  Vec3 wo = direction(40);
  EXPECT_NEAR(bsdf.evalLocal(wo, direction(20, 2)).x, 0.7f / kPi, 1e-6f);
  BsdfSample s = bsdf.sampleLocal(wo, 0.5f, {0.3f, 0.7f});
  EXPECT_NEAR(s.weight().x, 0.7f, 1e-5f);
}

TEST(Bsdf, SmoothLimitsAreDeltaLobesWithFiniteValues) {
  for (float roughness : {0.0f, 1e-4f, 0.02f}) {
    for (float transmission : {0.0f, 1.0f}) {
      Material m;
      m.metallic = transmission > 0 ? 0 : 1, m.roughness = roughness;
      m.transmission = transmission, m.baseColor = Color(1.0f);
      Bsdf bsdf(m, Vec3{0, 0, 1}, 1.5f);
      EXPECT_FALSE(bsdf.hasNonDelta());
      for (float angle : {0.0f, 45.0f, 89.9f}) {
        Vec3 wo = direction(angle);
        for (float uc : {0.01f, 0.5f, 0.99f}) {
          BsdfSample s = bsdf.sampleLocal(wo, uc, {0.5f, 0.5f});
          ASSERT_TRUE(s.valid());
          EXPECT_TRUE(s.delta);
          EXPECT_TRUE(isFinite(s.weight()));
          // eval and pdf of a delta lobe are zero for every (measure-zero) direction.
          EXPECT_EQ(bsdf.pdfLocal(wo, s.wi), 0.0f);
          EXPECT_TRUE(isBlack(bsdf.evalLocal(wo, s.wi)));
        }
      }
    }
  }
}

TEST(Bsdf, SmoothMirrorReflectsWithSchlickFresnel) {
  Material m;
  m.metallic = 1, m.roughness = 0, m.baseColor = Color(0.9f, 0.5f, 0.2f);
  Bsdf bsdf(m, Vec3{0, 0, 1}, 1.5f);
  Vec3 wo = direction(60);
  BsdfSample s = bsdf.sampleLocal(wo, 0.5f, {0.1f, 0.2f});
  EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
  EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
  float m5 = std::pow(1 - 0.5f, 5.0f);
  EXPECT_NEAR(s.weight().z, 0.2f + 0.8f * m5, 1e-5f);
}

}  // namespace
}  // namespace tray

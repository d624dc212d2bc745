// KHR_materials_specular and KHR_materials_clearcoat in the Bsdf: sampling against the pdf (chi
// square), sample/eval/pdf agreement, energy (one-bounce white furnace), and closed forms:
// a smooth coat over Lambert reflects Fc + (1 - Fc) albedo; specular 0 leaves pure Lambert;
// specularColor tints F0 exactly at normal incidence. KHR_materials_sheen likewise, and its
// albedo table against Monte Carlo integration of the Charlie BRDF.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/bsdf.h"
#include "materials/fresnel.h"
#include "materials/sheen.h"
#include "tests/materials/chi2.h"

namespace tray {
namespace {

Vec3 direction(float thetaDeg, float phi = 0.3f) {
  float t = thetaDeg * kPi / 180;
  return {std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)};
}

Material material(float metallic, float roughness, float transmission, const Color& base) {
  Material m;
  m.baseColor = base, m.metallic = metallic, m.roughness = roughness;
  m.transmission = transmission;
  return m;
}

/// E[f |cos| / pdf] over BSDF samples from wo: the directional albedo (per channel).
Color albedo(const Bsdf& bsdf, const Vec3& wo, int n = 100000) {
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    float a = (i + 0.5f) / n, b = (i * 0.618034f) - std::floor(i * 0.618034f);
    float uc = (i * 0.754878f) - std::floor(i * 0.754878f);
    BsdfSample s = bsdf.sample(wo, uc, {a, b});
    if (!s.valid()) continue;
    const double w = std::fabs(dot(s.wi, bsdf.frame().n)) / s.pdf / s.etaScale;
    for (int k = 0; k < 3; ++k) sum[k] += s.f[k] * w;
  }
  return {float(sum[0] / n), float(sum[1] / n), float(sum[2] / n)};
}

struct CoatCase {
  const char* name;
  float metallic, roughness, transmission, coatRoughness;
  Vec3 coatNormal;  ///< (0, 0, 1): the base's normal
};

const CoatCase kCoats[] = {
    {"OverLambert", 0, 1, 0, 0.3f, {0, 0, 1}},
    {"OverPlastic", 0, 0.5f, 0, 0.2f, {0, 0, 1}},
    {"OverMetal", 1, 0.6f, 0, 0.4f, {0, 0, 1}},
    {"OverRoughGlass", 0, 0.6f, 1, 0.3f, {0, 0, 1}},
    {"TiltedCoatNormal", 0, 0.8f, 0, 0.3f, {0.3f, 0.1f, 0.95f}},
};
const float kAngles[] = {10, 50, 80};

Bsdf coated(const CoatCase& c, const Color& base = Color(1.0f), float clearcoat = 1.0f) {
  ShadingMaterial sm =
      ShadingMaterial::of(material(c.metallic, c.roughness, c.transmission, base), {0, 0, 1});
  sm.clearcoat = clearcoat;
  sm.clearcoatRoughness = c.coatRoughness;
  sm.clearcoatN = normalize(c.coatNormal);
  return Bsdf(sm, Vec3{0, 0, 1}, 1.5f);
}

class Clearcoat : public ::testing::TestWithParam<CoatCase> {};

TEST_P(Clearcoat, SamplingMatchesPdfChiSquare) {
  const CoatCase c = GetParam();
  const Bsdf bsdf = coated(c, Color(0.6f), 0.8f);
  for (float angle : kAngles) {
    const Vec3 wo = direction(angle);
    auto sample = [&](Vec2 u, float uc, Vec3& wi) {
      BsdfSample s = bsdf.sample(wo, uc, u);
      if (!s.valid()) return false;
      EXPECT_FALSE(s.delta);
      wi = s.wi;
      return true;
    };
    auto pdf = [&](const Vec3& wi) { return bsdf.pdf(wo, wi); };
    test::Chi2Result r = test::chi2Test(sample, pdf, 200000, 31 + uint64_t(angle));
    const double alpha = 1 - std::pow(0.99, 1.0 / (std::size(kCoats) * std::size(kAngles)));
    EXPECT_GT(r.pValue, alpha) << c.name << " theta_o " << angle << ": chi2 " << r.statistic;
    EXPECT_NEAR(r.pdfIntegral, r.sampledFraction, 0.01) << c.name << " theta_o " << angle;
  }
}

/// Every sample's value and pdf agree with eval() and pdf() in the sampled direction (a
/// low-discrepancy sweep of 2000 samples at each of kAngles).
void expectSamplesMatchEvalAndPdf(const Bsdf& bsdf, const std::string& name) {
  for (float angle : kAngles) {
    const Vec3 wo = direction(angle);
    for (int i = 0; i < 2000; ++i) {
      float a = (i * 0.618034f) - std::floor(i * 0.618034f);
      float b = (i * 0.754878f) - std::floor(i * 0.754878f);
      float uc = (i * 0.569840f) - std::floor(i * 0.569840f);
      BsdfSample s = bsdf.sample(wo, uc, {a, b});
      if (!s.valid()) continue;
      const Color f = bsdf.eval(wo, s.wi);
      const float pdf = bsdf.pdf(wo, s.wi);
      ASSERT_TRUE(isFinite(s.f) && std::isfinite(s.pdf));
      EXPECT_NEAR(s.pdf, pdf, 1e-3f * pdf + 1e-6f) << name << " " << angle;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.f[k], f[k], 1e-3f * f[k] + 1e-6f) << name;
    }
  }
}

TEST_P(Clearcoat, SampleAgreesWithEvalAndPdf) {
  const CoatCase c = GetParam();
  const Bsdf bsdf = coated(c, Color(0.8f, 0.5f, 0.3f), 0.7f);
  expectSamplesMatchEvalAndPdf(bsdf, c.name);
}

TEST_P(Clearcoat, ReflectsAtMostTheEnergyItReceives) {
  const CoatCase c = GetParam();
  const Bsdf bsdf = coated(c);
  for (float angle : {0.5f, 30.0f, 60.0f, 85.0f}) {
    const Color a = albedo(bsdf, direction(angle));
    EXPECT_LE(a.x, 1.01) << c.name << " theta_o " << angle;
    EXPECT_GT(a.x, 0.3) << c.name << " theta_o " << angle;
  }
}

INSTANTIATE_TEST_SUITE_P(Layers, Clearcoat, ::testing::ValuesIn(kCoats),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Clearcoat, SmoothCoatOverLambertReflectsFresnelPlusTheRest) {
  // A mirror coat (F = Fc(cos_o)) over Lambert of albedo a: albedo = c Fc + (1 - c Fc) a, exactly
  // (the coat's delta sample carries c Fc, the base's samples (1 - c Fc) a).
  const CoatCase c{"SmoothOverLambert", 0, 1, 0, 0.0f, {0, 0, 1}};
  for (float cc : {1.0f, 0.5f}) {
    const Bsdf bsdf = coated(c, Color(0.5f, 0.25f, 0.0f), cc);
    for (float angle : {5.0f, 45.0f, 75.0f}) {
      const Vec3 wo = direction(angle);
      const float cFc = cc * fresnelDielectric(wo.z, 1.5f);
      const Color a = albedo(bsdf, wo, 20000);
      EXPECT_NEAR(a.x, cFc + (1 - cFc) * 0.5f, 2e-3f) << angle;
      EXPECT_NEAR(a.y, cFc + (1 - cFc) * 0.25f, 2e-3f) << angle;
      EXPECT_NEAR(a.z, cFc, 2e-3f) << angle;
    }
  }
}

TEST(Clearcoat, ZeroClearcoatIsTheBaseBitForBit) {
  const Material m = material(0, 0.5f, 0, Color(0.7f, 0.4f, 0.2f));
  const Frame frame = Frame::fromNormal(normalize(Vec3(0.2f, 0.1f, 1)));
  ShadingMaterial sm = ShadingMaterial::of(m, frame.n);
  sm.clearcoatRoughness = 0.3f;  // clearcoat 0: the roughness must not matter
  const Bsdf plain(m, frame.n, 1.5f), zero(sm, frame.n, 1.5f);
  for (int i = 0; i < 100; ++i) {
    const Vec3 wo = frame.toWorld(direction(3.0f + i * 0.8f, i * 1.3f));
    const Vec3 wi = frame.toWorld(direction(5.0f + i * 0.7f, i * 2.4f));
    float p1, p2;
    const Color f1 = plain.eval(wo, wi, p1), f2 = zero.eval(wo, wi, p2);
    EXPECT_TRUE(f1 == f2 && p1 == p2);
    const BsdfSample s1 = plain.sample(wo, 0.37f, {0.2f, 0.9f}), s2 = zero.sample(wo, 0.37f, {0.2f, 0.9f});
    EXPECT_TRUE(s1.wi == s2.wi && s1.f == s2.f && s1.pdf == s2.pdf);
  }
}

TEST(Specular, ZeroSpecularLeavesPureLambert) {
  ShadingMaterial sm = ShadingMaterial::of(material(0, 0.4f, 0, Color(1.0f)), {0, 0, 1});
  sm.specular = 0;
  const Bsdf bsdf(sm, Vec3{0, 0, 1}, 1.5f);
  for (float angle : {10.0f, 45.0f, 80.0f}) {
    const Vec3 wo = direction(angle), mirror{-wo.x, -wo.y, wo.z};
    // No specular peak: the mirror direction sees the Lambert value, 1/pi.
    EXPECT_NEAR(bsdf.eval(wo, mirror).x, 1 / kPi, 1e-6f) << angle;
    EXPECT_NEAR(albedo(bsdf, wo).x, 1.0f, 2e-3f) << angle;
  }
  // With specular 1 the same material does have a peak there.
  const Bsdf plain(material(0, 0.4f, 0, Color(1.0f)), Vec3{0, 0, 1}, 1.5f);
  const Vec3 wo = direction(10);
  EXPECT_GT(plain.eval(wo, {-wo.x, -wo.y, wo.z}).x, 1.2f / kPi);
}

TEST(Specular, ColourTintsF0AndKeepsF90) {
  const Color colour(1.0f, 0.5f, 0.25f);
  const GgxReflectionLobe lobe = GgxReflectionLobe::dielectric(0.1f, 1.5f, 0.8f, colour);
  const Color f0 = lobe.fresnel(1.0f), f90 = lobe.fresnel(0.0f);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(f0[k], 0.8f * 0.04f * colour[k], 1e-6f);  // min(F0 colour, 1) x specular
    EXPECT_NEAR(f90[k], 0.8f, 1e-6f);                      // F90 = specular
  }
  // Colour 1 and weight 1: the plain dielectric Fresnel.
  const GgxReflectionLobe plain = GgxReflectionLobe::dielectric(0.1f, 1.5f);
  const GgxReflectionLobe one = GgxReflectionLobe::dielectric(0.1f, 1.5f, 1.0f, Color(1.0f));
  for (float c : {0.05f, 0.3f, 0.7f, 1.0f}) EXPECT_NEAR(one.fresnel(c).x, plain.fresnel(c).x, 1e-6f);
  // In the Bsdf: black base, straight reflection at normal incidence: f ~ F0' per channel.
  ShadingMaterial sm = ShadingMaterial::of(material(0, 0.3f, 0, Color(0.0f)), {0, 0, 1});
  sm.specularColor = colour;
  const Bsdf bsdf(sm, Vec3{0, 0, 1}, 1.5f);
  const Color f = bsdf.eval({0, 0, 1}, {0, 0, 1});
  EXPECT_NEAR(f.y / f.x, 0.5f, 1e-5f);
  EXPECT_NEAR(f.z / f.x, 0.25f, 1e-5f);
  for (float angle : {10.0f, 60.0f, 85.0f}) {  // and never more than it receives
    const Color a = albedo(bsdf, direction(angle));
    EXPECT_LE(maxComponent(a), 1.0f) << angle;
  }
}

struct SheenCase {
  const char* name;
  float metallic, roughness, transmission, sheenRoughness, clearcoat;
};

const SheenCase kSheens[] = {
    {"OverLambert", 0, 1, 0, 0.5f, 0},
    {"SharpOverPlastic", 0, 0.5f, 0, 0.2f, 0},
    {"OverMetal", 1, 0.5f, 0, 0.8f, 0},
    {"UnderClearcoat", 0, 0.7f, 0, 0.4f, 0.8f},
};

Bsdf sheened(const SheenCase& c, const Color& base, const Color& sheenColor) {
  ShadingMaterial sm =
      ShadingMaterial::of(material(c.metallic, c.roughness, c.transmission, base), {0, 0, 1});
  sm.sheenColor = sheenColor;
  sm.sheenRoughness = c.sheenRoughness;
  sm.clearcoat = c.clearcoat;
  sm.clearcoatRoughness = 0.3f;
  return Bsdf(sm, Vec3{0, 0, 1}, 1.5f);
}

class Sheen : public ::testing::TestWithParam<SheenCase> {};

TEST_P(Sheen, SamplingMatchesPdfChiSquare) {
  const SheenCase c = GetParam();
  const Bsdf bsdf = sheened(c, Color(0.6f), Color(0.9f, 0.7f, 0.6f));
  for (float angle : kAngles) {
    const Vec3 wo = direction(angle);
    auto sample = [&](Vec2 u, float uc, Vec3& wi) {
      BsdfSample s = bsdf.sample(wo, uc, u);
      if (!s.valid()) return false;
      wi = s.wi;
      return true;
    };
    auto pdf = [&](const Vec3& wi) { return bsdf.pdf(wo, wi); };
    test::Chi2Result r = test::chi2Test(sample, pdf, 200000, 53 + uint64_t(angle));
    const double alpha = 1 - std::pow(0.99, 1.0 / (std::size(kSheens) * std::size(kAngles)));
    EXPECT_GT(r.pValue, alpha) << c.name << " theta_o " << angle << ": chi2 " << r.statistic;
    EXPECT_NEAR(r.pdfIntegral, r.sampledFraction, 0.01) << c.name << " theta_o " << angle;
  }
}

TEST_P(Sheen, SampleAgreesWithEvalAndPdf) {
  const SheenCase c = GetParam();
  const Bsdf bsdf = sheened(c, Color(0.8f, 0.5f, 0.3f), Color(0.2f, 0.5f, 0.9f));
  expectSamplesMatchEvalAndPdf(bsdf, c.name);
}

TEST_P(Sheen, ReflectsAtMostTheEnergyItReceives) {
  const SheenCase c = GetParam();
  const Bsdf bsdf = sheened(c, Color(1.0f), Color(1.0f));
  for (float angle : {0.5f, 30.0f, 60.0f, 85.0f}) {
    const Color a = albedo(bsdf, direction(angle));
    EXPECT_LE(a.x, 1.01) << c.name << " theta_o " << angle;
    EXPECT_GT(a.x, 0.3) << c.name << " theta_o " << angle;
  }
}

INSTANTIATE_TEST_SUITE_P(Layers, Sheen, ::testing::ValuesIn(kSheens),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(Sheen, AlbedoTableMatchesMonteCarlo) {
  // E(cos_o) = integral f |cos_i| dwi, estimated with cosine-weighted directions (f pi / N).
  for (float roughness : {0.1f, 0.3f, 0.6f, 1.0f}) {
    const CharlieSheen sheen(roughness);
    for (float angle : {5.0f, 40.0f, 70.0f, 85.0f}) {
      const Vec3 wo = direction(angle);
      const int n = 200000;
      double sum = 0;
      for (int i = 0; i < n; ++i) {
        const float a = (i + 0.5f) / n, b = (i * 0.618034f) - std::floor(i * 0.618034f);
        sum += sheen.eval(wo, sampleCosineHemisphere(Vec2{a, b})) * kPi;
      }
      const double E = sum / n;
      EXPECT_NEAR(sheen.albedo(wo.z), E, 0.01 + 0.02 * E) << roughness << " " << angle;
      EXPECT_LE(sheen.albedo(wo.z), 1.0f);
    }
  }
}

TEST(Sheen, ADirectionAlongTheNormalRoundedPastOneIsNoNaN) {
  // A unit vector along the normal may carry cos = 1.0000001 after renormalisation: the
  // masking fit took pow(1 - cos, C) of a negative number and the sample became NaN.
  const Vec3 along(0.0f, 0.0f, 1.0000001f);
  ASSERT_GT(along.z, 1.0f);
  for (float roughness : {0.07f, 0.3f, 0.5f, 1.0f}) {
    const CharlieSheen sheen(roughness);
    const Vec3 other = normalize(Vec3(0.3f, 0.1f, 0.9f));
    EXPECT_TRUE(std::isfinite(sheen.eval(along, other))) << roughness;
    EXPECT_TRUE(std::isfinite(sheen.eval(other, along))) << roughness;
    EXPECT_TRUE(std::isfinite(sheen.eval(along, along))) << roughness;
    EXPECT_TRUE(std::isfinite(sheen.albedo(along.z))) << roughness;
  }
}

TEST(Sheen, OverABlackBaseReflectsColourTimesAlbedo) {
  const SheenCase c{"OverBlack", 0, 1, 0, 0.5f, 0};
  const Color colour(1.0f, 0.5f, 0.25f);
  const Bsdf bsdf = sheened(c, Color(0.0f), colour);
  for (float angle : {20.0f, 60.0f, 80.0f}) {
    const Vec3 wo = direction(angle);
    const Color a = albedo(bsdf, wo);
    const float E = CharlieSheen(0.5f).albedo(wo.z);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], colour[k] * E, 0.01f + 0.02f * E) << angle;
  }
}

TEST(Sheen, BlackSheenIsTheBaseBitForBit) {
  const Material m = material(0, 0.5f, 0, Color(0.7f, 0.4f, 0.2f));
  const Frame frame = Frame::fromNormal(normalize(Vec3(0.2f, 0.1f, 1)));
  ShadingMaterial sm = ShadingMaterial::of(m, frame.n);
  sm.sheenRoughness = 0.3f;  // sheenColor 0 disables the layer whatever the roughness
  const Bsdf plain(m, frame.n, 1.5f), zero(sm, frame.n, 1.5f);
  for (int i = 0; i < 100; ++i) {
    const Vec3 wo = frame.toWorld(direction(3.0f + i * 0.8f, i * 1.3f));
    const Vec3 wi = frame.toWorld(direction(5.0f + i * 0.7f, i * 2.4f));
    float p1, p2;
    const Color f1 = plain.eval(wo, wi, p1), f2 = zero.eval(wo, wi, p2);
    EXPECT_TRUE(f1 == f2 && p1 == p2);
    const BsdfSample s1 = plain.sample(wo, 0.37f, {0.2f, 0.9f}), s2 = zero.sample(wo, 0.37f, {0.2f, 0.9f});
    EXPECT_TRUE(s1.wi == s2.wi && s1.f == s2.f && s1.pdf == s2.pdf);
  }
}

// Light-path AOVs (core/light_paths.h) split eval by lobe kind: the parts sum to eval, and each
// lobe lands in its kind (Lambert and sheen: diffuse; metal, coats, a dielectric's reflection:
// specular; its refraction: transmission).
TEST(EvalLobes, PartsSumToEvalAndLandInTheirKind) {
  const Vec3 wo = direction(40), up = direction(30, 2.0f), down = -direction(25, 1.0f);
  const Color base(0.7f, 0.5f, 0.3f);
  std::vector<Bsdf> all;
  for (const CoatCase& c : kCoats) all.push_back(coated(c, base, 0.7f));
  for (const SheenCase& c : kSheens) all.push_back(sheened(c, base, Color(0.9f, 0.7f, 0.6f)));
  for (float transmission : {0.0f, 0.5f, 1.0f})
    all.emplace_back(material(0.0f, 0.4f, transmission, base), Vec3{0, 0, 1}, 1.5f);
  for (const Bsdf& b : all)
    for (const Vec3& wi : {up, down}) {
      const LobeSplit s = b.evalLobes(wo, wi);
      const Color f = b.eval(wo, wi), sum = s.diffuse + s.specular + s.transmission;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], f[c], 1e-6f * std::max(1.0f, f[c]));
      if (wi.z < 0) {
        EXPECT_TRUE(isBlack(s.diffuse) && isBlack(s.specular));
      }
      if (wi.z > 0) {
        EXPECT_TRUE(isBlack(s.transmission));
      }
    }
  // Pure kinds: Lambert is all diffuse, a metal all specular, rough glass all specular above
  // and all transmission below.
  const Vec3 z{0, 0, 1};
  const LobeSplit lambert = Bsdf(material(0, 1, 0, base), z, 1.5f).evalLobes(wo, up);
  EXPECT_TRUE(!isBlack(lambert.diffuse) && isBlack(lambert.specular));
  const LobeSplit metal = Bsdf(material(1, 0.4f, 0, base), z, 1.5f).evalLobes(wo, up);
  EXPECT_TRUE(isBlack(metal.diffuse) && !isBlack(metal.specular));
  const Bsdf glass(material(0, 0.4f, 1, base), z, 1.5f);
  EXPECT_FALSE(isBlack(glass.evalLobes(wo, down).transmission));
  EXPECT_FALSE(isBlack(glass.evalLobes(wo, up).specular));
}

}  // namespace
}  // namespace tray

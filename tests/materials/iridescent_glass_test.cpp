// KHR_materials_iridescence on glass (materials/dielectric.h, DielectricLobe::setIridescence):
// the film's colour is what the glass reflects, what it does not reflect is transmitted, the
// same film reflects the same from inside at the refracted angle, sampling and pdf agree, and
// a factor of 0 is plain glass bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "materials/dielectric.h"
#include "materials/ggx_reflection.h"

namespace tray {
namespace {

constexpr float kEta = 1.5f, kFilmIor = 1.3f, kNm = 450.0f;

DielectricLobe filmGlass(float alpha, float factor = 1.0f) {
  DielectricLobe lobe(alpha, kEta, Color(1.0f));
  lobe.setIridescence(factor, kFilmIor, kNm);
  return lobe;
}

/// The smooth lobe's reflectance colour at wo: f |cos| of its reflection sample.
Color smoothReflectance(const DielectricLobe& lobe, const Vec3& wo) {
  const BsdfSample s = lobe.sample(wo, 0.0f, {0.5f, 0.5f});  // uc 0: reflection
  EXPECT_FALSE(s.transmission);
  return s.f * std::fabs(s.wi.z);
}

/// Uniform numbers in [0, 1) for the sampling tests.
struct Uniform {
  explicit Uniform(unsigned seed) : rng(seed) {}
  float get1D() { return std::min(dist(rng), 0.99999994f); }
  Vec2 get2D() {
    const float a = get1D();
    return {a, get1D()};
  }
  std::mt19937 rng;
  std::uniform_real_distribution<float> dist{0.0f, 1.0f};
};

Vec3 direction(float cosTheta, float phi) {
  const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

TEST(IridescentGlass, ReflectsTheSameFilmAsTheCoat) {
  // The coat (GgxReflectionLobe) carries the same film over the same F0 through its own code.
  GgxReflectionLobe coat = GgxReflectionLobe::dielectric(0.0f, kEta);
  coat.setIridescence(1.0f, kFilmIor, kNm);
  const DielectricLobe glass = filmGlass(0.0f);
  for (float c : {1.0f, 0.8f, 0.5f, 0.2f}) {
    const Color expected = coat.fresnel(c), got = smoothReflectance(glass, direction(c, 0.3f));
    EXPECT_NEAR(got.x, expected.x, 1e-5f) << c;
    EXPECT_NEAR(got.y, expected.y, 1e-5f) << c;
    EXPECT_NEAR(got.z, expected.z, 1e-5f) << c;
  }
  // A 450 nm film is coloured: its channels differ by more than plain glass's grey allows.
  const Color r = smoothReflectance(glass, {0, 0, 1});
  EXPECT_GT(std::max({r.x, r.y, r.z}) - std::min({r.x, r.y, r.z}), 0.01f) << r.x << " " << r.y;
}

TEST(IridescentGlass, TransmitsWhatItDoesNotReflect) {
  const DielectricLobe glass = filmGlass(0.0f);
  const Vec3 wo = direction(0.7f, 1.0f);
  const Color R = smoothReflectance(glass, wo);
  const BsdfSample t = glass.sample(wo, 0.999f, {0.5f, 0.5f});
  ASSERT_TRUE(t.transmission);
  // f |cos_t| = (1 - R) / eta'^2 and etaScale = 1 / eta'^2: the radiance-free share is 1 - R.
  const Color T = t.f * std::fabs(t.wi.z) / t.etaScale;
  EXPECT_NEAR(R.x + T.x, 1.0f, 1e-5f);
  EXPECT_NEAR(R.y + T.y, 1.0f, 1e-5f);
  EXPECT_NEAR(R.z + T.z, 1.0f, 1e-5f);
  // Reflection is chosen with the mean reflectance, so each sample's weight stays bounded.
  const BsdfSample r = glass.sample(wo, 0.0f, {0.5f, 0.5f});
  EXPECT_NEAR(r.pdf, (R.x + R.y + R.z) / 3.0f, 1e-6f);
  EXPECT_NEAR(t.pdf, 1.0f - r.pdf, 1e-6f);
}

TEST(IridescentGlass, ReflectsFromInsideAsFromOutsideAtTheRefractedAngle) {
  const DielectricLobe glass = filmGlass(0.0f);
  for (float cosOut : {1.0f, 0.9f, 0.6f, 0.3f}) {
    const float sinIn = std::sqrt(1.0f - cosOut * cosOut) / kEta;
    const float cosIn = std::sqrt(1.0f - sinIn * sinIn);
    const Color outside = smoothReflectance(glass, direction(cosOut, 0.0f));
    const Color inside = smoothReflectance(glass, direction(-cosIn, 0.0f));
    EXPECT_NEAR(inside.x, outside.x, 2e-4f) << cosOut;
    EXPECT_NEAR(inside.y, outside.y, 2e-4f) << cosOut;
    EXPECT_NEAR(inside.z, outside.z, 2e-4f) << cosOut;
  }
  // Beyond the critical angle the film does not change total internal reflection.
  const Color tir = smoothReflectance(glass, direction(-0.3f, 0.0f));
  EXPECT_FLOAT_EQ(tir.x, 1.0f);
  EXPECT_FLOAT_EQ(tir.z, 1.0f);
}

TEST(IridescentGlass, RoughSamplesAgreeWithEvalAndPdf) {
  const DielectricLobe glass = filmGlass(0.3f);
  Uniform sampler(7);
  int checked = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 wo = direction(i % 2 ? 0.6f : -0.8f, 0.1f * float(i));
    const BsdfSample s = glass.sample(wo, sampler.get1D(), sampler.get2D());
    if (!(s.pdf > 0)) continue;
    const float pdf = glass.pdf(wo, s.wi);
    const Color f = glass.eval(wo, s.wi);
    EXPECT_NEAR(s.pdf, pdf, 1e-4f * std::max(1.0f, pdf));
    EXPECT_NEAR(s.f.y, f.y, 1e-4f * std::max(1.0f, f.y));
    ++checked;
  }
  EXPECT_GT(checked, 3000);
}

TEST(IridescentGlass, RoughAlbedoIsAtMostOneAndCloseToPlainGlass) {
  // The directional albedo, sum over samples of f |cos| / pdf with the radiance scale taken
  // out: a film only moves energy between reflection and transmission (and between colours).
  const DielectricLobe film = filmGlass(0.3f), plain(0.3f, kEta, Color(1.0f));
  const Vec3 wo = direction(0.8f, 0.0f);
  Color a(0.0f), b(0.0f);
  const int n = 200000;
  Uniform sampler(11);
  for (int i = 0; i < n; ++i) {
    const float uc = sampler.get1D();
    const Vec2 u = sampler.get2D();
    for (int k = 0; k < 2; ++k) {
      const DielectricLobe& lobe = k ? plain : film;
      const BsdfSample s = lobe.sample(wo, uc, u);
      if (!(s.pdf > 0)) continue;
      (k ? b : a) += s.f * (std::fabs(s.wi.z) / s.pdf / s.etaScale);
    }
  }
  a /= float(n), b /= float(n);
  for (float c : {a.x, a.y, a.z}) {
    EXPECT_LE(c, 1.01f);
    EXPECT_NEAR(c, b.y, 0.03f);  // the GGX interface's own loss, the same with or without film
  }
}

TEST(IridescentGlass, FactorZeroIsPlainGlassBitForBit) {
  for (float alpha : {0.0f, 0.25f}) {
    const DielectricLobe off = filmGlass(alpha, 0.0f), plain(alpha, kEta, Color(1.0f));
    EXPECT_FALSE(off.iridescent());
    Uniform sampler(3);
    for (int i = 0; i < 500; ++i) {
      const Vec3 wo = direction(i % 3 ? 0.7f : -0.5f, float(i));
      const float uc = sampler.get1D();
      const Vec2 u = sampler.get2D();
      const BsdfSample x = off.sample(wo, uc, u), y = plain.sample(wo, uc, u);
      EXPECT_EQ(x.pdf, y.pdf);
      EXPECT_EQ(x.f.x, y.f.x);
      EXPECT_EQ(x.wi.z, y.wi.z);
      if (alpha > 0 && y.pdf > 0) {
        EXPECT_EQ(off.pdf(wo, y.wi), plain.pdf(wo, y.wi));
        EXPECT_EQ(off.eval(wo, y.wi).z, plain.eval(wo, y.wi).z);
      }
    }
  }
}

}  // namespace
}  // namespace tray

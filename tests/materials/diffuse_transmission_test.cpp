// KHR_materials_diffuse_transmission: the Lambert lobe becomes (1 - dt) Lambert(baseColor) on
// wo's side plus dt Lambert(colour) on the far side. Closed forms: a surface of roughness 1
// (no coat) reflects exactly (1 - dt) baseColor and transmits exactly dt colour; its samples
// follow its pdf over the whole sphere; a coat keeps the sum below 1.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/bsdf.h"
#include "materials/fresnel.h"
#include "tests/materials/chi2.h"

namespace tray {
namespace {

ShadingMaterial transmitter(float roughness, float dt, const Color& base, const Color& colour) {
  Material m;
  m.baseColor = base, m.metallic = 0, m.roughness = roughness;
  ShadingMaterial s = ShadingMaterial::of(m, Vec3(0, 0, 1));
  s.diffuseTransmission = dt;
  s.diffuseTransmissionColor = colour;
  return s;
}

Vec3 spherical(double theta, double phi) {
  return {float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
          float(std::cos(theta))};
}

/// Reflected and transmitted albedo at wo by quadrature of eval |cos_i| over each hemisphere.
void albedos(const Bsdf& bsdf, const Vec3& wo, Color& reflected, Color& transmitted) {
  reflected = transmitted = Color(0.0f);
  const int nt = 400, np = 64;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < np; ++j) {
      const double t = (i + 0.5) / nt * kPi, p = (j + 0.5) / np * 2 * kPi;
      const Vec3 wi = spherical(t, p);
      const float w = float(std::fabs(std::cos(t)) * std::sin(t) * (kPi / nt) * (2 * kPi / np));
      (wi.z * wo.z > 0 ? reflected : transmitted) += bsdf.eval(wo, wi) * w;
    }
}

TEST(DiffuseTransmission, AlbedosAreTheClosedForm) {
  const Color base(0.8f, 0.5f, 0.2f), colour(0.3f, 0.9f, 0.6f);
  const float dt = 0.4f;
  const ShadingMaterial sm = transmitter(1.0f, dt, base, colour);
  EXPECT_FALSE(Bsdf::isLambertOnly(sm)) << "the SIMD matte stage must not take it";
  EXPECT_FALSE(Bsdf::isGgxMixture(sm));
  const Bsdf bsdf(sm, Vec3(0, 0, 1), 1.5f);
  EXPECT_TRUE(bsdf.transmits());
  for (double theta : {0.2, 1.1, kPi - 0.5}) {  // from either side: thin and symmetric
    Color r, t;
    albedos(bsdf, spherical(theta, 0.3), r, t);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(r[k], (1 - dt) * base[k], 2e-3) << theta << " channel " << k;
      EXPECT_NEAR(t[k], dt * colour[k], 2e-3) << theta << " channel " << k;
    }
  }
  // dt = 1 transmits all (colour white: a perfect diffuser of the light behind).
  const Bsdf all(transmitter(1.0f, 1.0f, base, Color(1.0f)), Vec3(0, 0, 1), 1.5f);
  Color r, t;
  albedos(all, spherical(0.5, 0), r, t);
  EXPECT_NEAR(r.x, 0.0, 1e-6);
  EXPECT_NEAR(t.y, 1.0, 2e-3);
}

TEST(DiffuseTransmission, SamplesFollowThePdfOverTheSphere) {
  for (float roughness : {1.0f, 0.5f}) {  // alone, and under the plastic's GGX coat
    const Bsdf bsdf(transmitter(roughness, 0.6f, Color(0.7f), Color(0.5f, 1.0f, 0.5f)),
                    Vec3(0, 0, 1), 1.5f);
    for (double theta : {0.3, 1.2}) {
      const Vec3 wo = spherical(theta, 1.0);
      int transmitted = 0;
      auto sample = [&](Vec2 u, float uc, Vec3& wi) {
        const BsdfSample s = bsdf.sample(wo, uc, u);
        if (!s.valid()) return false;
        float pdf;
        const Color f = bsdf.eval(wo, s.wi, pdf);
        EXPECT_NEAR(s.pdf, pdf, 1e-4f * pdf);
        EXPECT_NEAR(s.f.y, f.y, 1e-4f * f.y + 1e-8f);
        EXPECT_EQ(s.transmission, s.wi.z < 0);
        transmitted += s.wi.z < 0;
        wi = s.wi;
        return true;
      };
      auto pdf = [&](const Vec3& wi) { return bsdf.pdf(wo, wi); };
      const test::Chi2Result r = test::chi2Test(sample, pdf, 200000, 21);
      EXPECT_GT(r.pValue, 0.01 / 4) << roughness << " " << theta << " chi2 " << r.statistic;
      // Coat reflections below the horizon are no sample: the pdf's mass is the valid fraction.
      EXPECT_NEAR(r.pdfIntegral, r.sampledFraction, 0.01);
      EXPECT_GT(transmitted, 20000);
    }
  }
}

TEST(DiffuseTransmission, CoatedSurfaceConservesEnergy) {
  // White base and colour under the plastic's coat (roughness 0.4: coat strength 1): the
  // diffuse part is weighted by 1 - F(cos_o) (materials/bsdf.h), so the transmitted albedo is
  // exactly dt (1 - F(cos_o)), and reflected + transmitted stays <= 1.
  const float dt = 0.5f;
  const Bsdf bsdf(transmitter(0.4f, dt, Color(1.0f), Color(1.0f)), Vec3(0, 0, 1), 1.5f);
  for (double theta : {0.2, 1.0, 1.4}) {
    Color r, t;
    albedos(bsdf, spherical(theta, 0.0), r, t);
    EXPECT_LE(r.x + t.x, 1.0f + 3e-3f) << theta;
    EXPECT_NEAR(t.x, dt * (1 - fresnelDielectric(float(std::cos(theta)), 1.5f)), 2e-3) << theta;
  }
}

TEST(DiffuseTransmission, ZeroFactorIsThePlainMaterial) {
  const Bsdf none(transmitter(0.5f, 0.0f, Color(0.6f), Color(1.0f)), Vec3(0, 0, 1), 1.5f);
  Material m;
  m.baseColor = Color(0.6f), m.metallic = 0, m.roughness = 0.5f;
  const Bsdf plain(m, Vec3(0, 0, 1), 1.5f);
  EXPECT_FALSE(none.transmits());
  const Vec3 wo = spherical(0.4, 0.2), wi = spherical(0.9, 2.5);
  EXPECT_EQ(none.eval(wo, wi).x, plain.eval(wo, wi).x);
  EXPECT_EQ(none.pdf(wo, wi), plain.pdf(wo, wi));
}

}  // namespace
}  // namespace tray

namespace tray {
namespace {

TEST(DiffuseTransmission, ImportanceScalesOnlyTheRefractedPart) {
  // With KHR_materials_transmission beside it, importance (bdpt, sppm) takes the 1/eta^2 of
  // refraction off the glass lobe only (Veach 1997, 5.2): the diffusely transmitted part is
  // not refracted.
  ShadingMaterial both = transmitter(0.5f, 0.5f, Color(0.8f), Color(0.6f));
  both.transmission = 0.5f;
  ShadingMaterial glass = both;
  glass.diffuseTransmission = 0;
  const float eta = 1.5f;
  const Bsdf a(both, Vec3(0, 0, 1), eta), b(glass, Vec3(0, 0, 1), eta);
  const Vec3 wo = spherical(0.5, 0.3), wi = spherical(2.6, 3.0);  // wi below
  float pdf;
  const Color importance = a.evalImportance(wo, wi, pdf);
  const Color expected = a.eval(wo, wi) + b.eval(wo, wi) * (eta * eta - 1);
  EXPECT_GT(b.eval(wo, wi).x, 0.0f);
  EXPECT_GT(a.eval(wo, wi).x, b.eval(wo, wi).x);  // the diffuse transmission adds
  EXPECT_NEAR(importance.x, expected.x, 1e-5f * expected.x);
  // Above the surface nothing changes.
  const Vec3 up = spherical(0.9, 2.0);
  EXPECT_EQ(a.evalImportance(wo, up, pdf).x, a.eval(wo, up).x);
}

}  // namespace
}  // namespace tray

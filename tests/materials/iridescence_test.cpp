// KHR_materials_iridescence (materials/iridescence.h): the thin-film Fresnel against an
// independent double-precision Airy computation, and the extension's off switches (factor 0,
// thickness 0) leaving the plain Fresnel bit for bit.
//
// The reference: for each wavelength, the exact Airy reflectance of the film (two-interface
// Fresnel amplitudes with the film's phase 4 pi n2 d cos2 / lambda, s and p averaged), the
// same with the phase averaged out (the incoherent sum C0), and
//   RGB = C0 + M_709 int (R(lambda) - C0) xyz(lambda) dlambda / int ybar dlambda
// with the CIE 1931 matching functions from Wyman, Sloan & Shirley 2013's multi-lobe fit (not
// Belcour & Barla's Fourier-space Gaussians). This is the reference implementation's colour
// convention: the spectrally flat part of the reflectance is white, the oscillating part is
// taken through XYZ -> Rec.709 (docs/materials-iridescence-dispersion.md, "Limits").
#include "materials/iridescence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "materials/bsdf.h"
#include "materials/ggx_reflection.h"

namespace tray {
namespace {

using cd = std::complex<double>;

double lobe(double l, double mu, double s1, double s2) {
  const double t = (l - mu) / (l < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}
void cie(double l, double xyz[3]) {
  xyz[0] = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
           0.065 * lobe(l, 501.1, 20.4, 26.2);
  xyz[1] = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
  xyz[2] = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
}

/// Fresnel amplitude coefficients (s, p) from medium a to b at cosines ca, cb.
void amplitudes(double na, double nb, double ca, double cb, double& rs, double& rp) {
  rs = (na * ca - nb * cb) / (na * ca + nb * cb);
  rp = (nb * ca - na * cb) / (nb * ca + na * cb);
}

/// Airy reflectance of film n2 (thickness d nm) between n1 and n3 at wavelength lambda, and the
/// incoherent (phase-averaged) sum; both averaged over s and p.
void airy(double n1, double n2, double n3, double cos1, double d, double lambda, double& R,
          double& C0) {
  const double sin1 = std::sqrt(1 - cos1 * cos1);
  const double cos2 = std::sqrt(1 - (n1 * sin1 / n2) * (n1 * sin1 / n2));
  const double cos3 = std::sqrt(1 - (n1 * sin1 / n3) * (n1 * sin1 / n3));
  double r12[2], r23[2];
  amplitudes(n1, n2, cos1, cos2, r12[0], r12[1]);
  amplitudes(n2, n3, cos2, cos3, r23[0], r23[1]);
  const double delta = 4 * M_PI * n2 * d * cos2 / lambda;
  const cd e = std::polar(1.0, delta);
  R = 0, C0 = 0;
  for (int k = 0; k < 2; ++k) {
    const cd r = (r12[k] + r23[k] * e) / (1.0 + r12[k] * r23[k] * e);
    R += 0.5 * std::norm(r);
    const double R12 = r12[k] * r12[k], R23 = r23[k] * r23[k], T = 1 - R12;
    C0 += 0.5 * (R12 + T * T * R23 / (1 - R12 * R23));
  }
}

Color reference(double n2, double n3, double cos1, double d) {
  double sum[3] = {0, 0, 0}, ybar = 0, C0 = 0;
  for (double l = 360; l <= 830; l += 0.25) {
    double R, c0, xyz[3];
    airy(1.0, n2, n3, cos1, d, l, R, c0);
    cie(l, xyz);
    for (int k = 0; k < 3; ++k) sum[k] += (R - c0) * xyz[k];
    ybar += xyz[1];
    C0 = c0;
  }
  for (double& s : sum) s /= ybar;
  return {float(C0 + 3.2404542 * sum[0] - 1.5371385 * sum[1] - 0.4985314 * sum[2]),
          float(C0 - 0.9692660 * sum[0] + 1.8760108 * sum[1] + 0.0415560 * sum[2]),
          float(C0 + 0.0556434 * sum[0] - 0.2040259 * sum[1] + 1.0572252 * sum[2])};
}

// A soap-like film (n 1.33 and 1.3 as the extension's default) over glass (n 1.5, F0 0.04)
// and over a denser dielectric (n 2.0, F0 0.111). At normal incidence Schlick's interface
// reflectances are exact, so what differs from the reference is the spectral integration
// (Belcour & Barla's Gaussian fits in Fourier space against Wyman et al.'s fit, Airy series
// cut at m = 2), which grows with the optical path difference: within 0.012 in absolute
// reflectance (measured max printed; out-of-gamut negative values clamp to 0 on both sides).
TEST(Iridescence, MatchesAiryAtNormalIncidence) {
  double worst = 0;
  for (double n2 : {1.3, 1.33})
    for (double n3 : {1.5, 2.0})
      for (double d = 50; d <= 1000; d += 25) {
        const double f0 = (n3 - 1) * (n3 - 1) / ((n3 + 1) * (n3 + 1));
        const Color got = iridescentFresnel(1.0f, float(n2), 1.0f, float(d), Color(float(f0)));
        const Color want = reference(n2, n3, 1.0, d);
        for (int k = 0; k < 3; ++k) {
          const double w = std::max(double(want[k]), 0.0);  // both clamp out-of-gamut at 0
          EXPECT_NEAR(got[k], w, 0.012) << "n2 " << n2 << " n3 " << n3 << " d " << d;
          worst = std::max(worst, std::fabs(double(got[k]) - w));
        }
      }
  std::printf("normal incidence: max |error| %.5f\n", worst);
}

// Oblique incidence adds Schlick's error at both interfaces (the reference implementation's
// choice) against the exact s/p Fresnel amplitudes: within 0.02 down to cos 0.5.
TEST(Iridescence, MatchesAiryObliquely) {
  double worst = 0;
  for (double cos1 : {0.9, 0.7, 0.5})
    for (double d = 100; d <= 800; d += 50) {
      const Color got = iridescentFresnel(1.0f, 1.3f, float(cos1), float(d), Color(0.04f));
      const Color want = reference(1.3, 1.5, cos1, d);
      for (int k = 0; k < 3; ++k) {
        const double w = std::max(double(want[k]), 0.0);
        EXPECT_NEAR(got[k], w, 0.02) << "cos " << cos1 << " d " << d;
        worst = std::max(worst, std::fabs(double(got[k]) - w));
      }
    }
  std::printf("oblique: max |error| %.5f\n", worst);
}

// The film colours: a 400 nm film over glass is not grey, and the colour changes with the
// thickness (a test that a constant would fail).
TEST(Iridescence, FilmIsColoured) {
  const Color a = iridescentFresnel(1.0f, 1.33f, 1.0f, 300.0f, Color(0.04f));
  const Color b = iridescentFresnel(1.0f, 1.33f, 1.0f, 500.0f, Color(0.04f));
  EXPECT_GT(maxComponent(a) - std::min({a.x, a.y, a.z}), 0.01f);
  EXPECT_GT(std::fabs(a.x - b.x) + std::fabs(a.z - b.z), 0.01f);
}

TEST(Iridescence, OffLeavesPlainFresnelExactly) {
  const float cosines[] = {1.0f, 0.8f, 0.5f, 0.1f};
  auto same = [&](GgxReflectionLobe plain, GgxReflectionLobe film) {
    for (float c : cosines) {
      const Color a = plain.fresnel(c), b = film.fresnel(c);
      EXPECT_EQ(a.x, b.x);
      EXPECT_EQ(a.y, b.y);
      EXPECT_EQ(a.z, b.z);
    }
    EXPECT_FALSE(film.iridescent());
  };
  for (int off = 0; off < 2; ++off) {
    const float factor = off ? 0.7f : 0.0f, thickness = off ? 0.0f : 400.0f;
    GgxReflectionLobe metal = GgxReflectionLobe::metal(0.1f, Color(0.9f, 0.6f, 0.3f));
    metal.setIridescence(factor, 1.3f, thickness);
    same(GgxReflectionLobe::metal(0.1f, Color(0.9f, 0.6f, 0.3f)), metal);
    GgxReflectionLobe coat = GgxReflectionLobe::dielectric(0.1f, 1.5f);
    coat.setIridescence(factor, 1.3f, thickness);
    same(GgxReflectionLobe::dielectric(0.1f, 1.5f), coat);
    GgxReflectionLobe tinted = GgxReflectionLobe::dielectric(0.1f, 1.5f, 0.8f, Color(1, 0.5f, 1));
    tinted.setIridescence(factor, 1.3f, thickness);
    same(GgxReflectionLobe::dielectric(0.1f, 1.5f, 0.8f, Color(1, 0.5f, 1)), tinted);
  }
}

// The whole BSDF: a plastic and a half-metal with the film off (thickness 0) evaluate and
// sample exactly as without the extension; with it on, the value changes.
TEST(Iridescence, BsdfOffIsPlainAndOnDiffers) {
  for (float metallic : {0.0f, 0.5f, 1.0f}) {
    Material plain;
    plain.baseColor = Color(0.8f, 0.5f, 0.2f), plain.metallic = metallic, plain.roughness = 0.3f;
    ShadingMaterial a = ShadingMaterial::of(plain, Vec3(0, 0, 1));
    ShadingMaterial off = a, on = a;
    off.iridescence = 1.0f, off.iridescenceThickness = 0.0f;
    on.iridescence = 1.0f, on.iridescenceThickness = 350.0f;
    const Bsdf b0(a, Vec3(0, 0, 1), 1.5f), b1(off, Vec3(0, 0, 1), 1.5f),
        b2(on, Vec3(0, 0, 1), 1.5f);
    const Vec3 wo = normalize(Vec3(0.3f, 0.1f, 0.9f)), wi = normalize(Vec3(-0.2f, -0.1f, 0.95f));
    float p0, p1, p2;
    const Color f0 = b0.eval(wo, wi, p0), f1 = b1.eval(wo, wi, p1), f2 = b2.eval(wo, wi, p2);
    EXPECT_EQ(f0.x, f1.x);
    EXPECT_EQ(f0.y, f1.y);
    EXPECT_EQ(f0.z, f1.z);
    EXPECT_EQ(p0, p1);
    EXPECT_GT(std::fabs(f0.x - f2.x) + std::fabs(f0.y - f2.y) + std::fabs(f0.z - f2.z), 1e-3f)
        << "metallic " << metallic;
    const BsdfSample s0 = b0.sample(wo, 0.37f, {0.2f, 0.7f}),
                     s1 = b1.sample(wo, 0.37f, {0.2f, 0.7f});
    EXPECT_EQ(s0.f.x, s1.f.x);
    EXPECT_EQ(s0.pdf, s1.pdf);
    // With the film, a sample's value is the mixture's eval there (metal and coat Fresnel).
    for (float uc : {0.05f, 0.37f, 0.9f}) {
      const BsdfSample s2 = b2.sample(wo, uc, {0.3f, 0.6f});
      if (!(s2.pdf > 0) || s2.delta) continue;
      float pe;
      const Color fe = b2.eval(wo, s2.wi, pe);
      EXPECT_NEAR(s2.f.x, fe.x, 1e-5f * (1 + fe.x));
      EXPECT_NEAR(s2.f.z, fe.z, 1e-5f * (1 + fe.z));
      EXPECT_NEAR(s2.pdf, pe, 1e-5f * (1 + pe));
    }
    // The SIMD glossy stage does not take the film: such vertices stay scalar.
    EXPECT_TRUE(Bsdf::isGgxMixture(a));
    EXPECT_TRUE(Bsdf::isGgxMixture(off));
    EXPECT_FALSE(Bsdf::isGgxMixture(on));
  }
}

}  // namespace
}  // namespace tray

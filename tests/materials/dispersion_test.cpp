// KHR_materials_dispersion's pieces (materials/dispersion.h): the Cauchy/Abbe IOR, and the
// wavelength sampler whose RGB weights keep white white in expectation.
#include "materials/dispersion.h"

#include <gtest/gtest.h>

#include <cmath>

#include "materials/medium_stack.h"

namespace tray {
namespace {

TEST(Dispersion, IorFollowsTheAbbeNumber) {
  // At the d line (587.56 nm) the IOR is n_d; the Abbe number V = (n_d - 1) / (n_F - n_C)
  // with F = 486.13 nm, C = 656.27 nm comes back as 20 / dispersion.
  const float nd = 1.5168f, dispersion = 20.0f / 64.17f;  // BK7-like
  EXPECT_NEAR(dispersiveIor(nd, dispersion, 587.56f), nd, 2e-4f);
  const float nF = dispersiveIor(nd, dispersion, 486.13f),
              nC = dispersiveIor(nd, dispersion, 656.27f);
  EXPECT_NEAR((nd - 1.0f) / (nF - nC), 64.17f, 1.0f);
  EXPECT_GT(dispersiveIor(nd, dispersion, 420.0f), dispersiveIor(nd, dispersion, 680.0f));
  EXPECT_EQ(dispersiveIor(nd, 0.0f, 450.0f), nd);
}

TEST(Dispersion, WeightsAverageToWhite) {
  // Stratified u over [0, 1): the mean weight is 1 per channel (the table's normalisation), and
  // each sample's weight is response / pdf.
  const int n = 200000;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    const WavelengthSample s = sampleWavelength((float(i) + 0.5f) / float(n));
    ASSERT_GE(s.lambda, kWavelengthMin);
    ASSERT_LT(s.lambda, kWavelengthMax);
    ASSERT_GT(s.pdf, 0.0f);
    EXPECT_FLOAT_EQ(s.pdf, wavelengthPdf(s.lambda));
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(s.weight[k], 0.0f);
      sum[k] += s.weight[k];
    }
  }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / n, 1.0, 2e-3) << "channel " << k;
  // Monochromatic light: 450 nm is blue, 530 green, 620 red.
  auto dominant = [](float l) {
    const Color c = wavelengthResponse(l);
    return c.x > c.y && c.x > c.z ? 0 : c.y > c.z ? 1 : 2;
  };
  EXPECT_EQ(dominant(450.0f), 2);
  EXPECT_EQ(dominant(530.0f), 1);
  EXPECT_EQ(dominant(620.0f), 0);
}

// The clamp of the Rec.709 curves' negative lobes against exact (signed) colorimetry: the
// RGB of a 20 nm band of light (what one pixel of a prism's spectrum sees) and of broad
// spectra. Measured and printed; the bounds are the figures in the docs, with a margin.
TEST(Dispersion, ClampErrorAgainstExactColorimetry) {
  double worstBand = 0, worstBroad = 0;
  for (float lo = 400; lo + 20 <= 700; lo += 10) {
    Color a(0.0f), b(0.0f);
    for (float l = lo + 0.5f; l < lo + 20; l += 1)
      a += wavelengthResponse(l), b += wavelengthResponseSigned(l);
    // Relative to the band's luminance-like scale (the sum of the exact channels' magnitudes).
    const double scale = std::fabs(b.x) + std::fabs(b.y) + std::fabs(b.z);
    for (int k = 0; k < 3; ++k) worstBand = std::max(worstBand, std::fabs(a[k] - b[k]) / scale);
  }
  // Broad spectra: a linear ramp (warm) and its reverse (cool) across the visible range.
  for (int dir = 0; dir < 2; ++dir) {
    Color a(0.0f), b(0.0f);
    for (float l = kWavelengthMin + 0.5f; l < kWavelengthMax; l += 1) {
      const float t = (l - kWavelengthMin) / (kWavelengthMax - kWavelengthMin);
      const float s = dir ? t : 1 - t;
      a += s * wavelengthResponse(l), b += s * wavelengthResponseSigned(l);
    }
    const double scale = std::fabs(b.x) + std::fabs(b.y) + std::fabs(b.z);
    for (int k = 0; k < 3; ++k) worstBroad = std::max(worstBroad, std::fabs(a[k] - b[k]) / scale);
  }
  std::printf("20 nm bands: max |clamped - exact| / sum|exact| = %.3f; broad ramps: %.3f\n",
              worstBand, worstBroad);
  EXPECT_LT(worstBand, 0.6);
  EXPECT_LT(worstBroad, 0.1);
}

TEST(Dispersion, MediumStackUsesTheWavelength) {
  Material glass;
  glass.transmission = 1, glass.metallic = 0, glass.ior = 1.5f;
  glass.layers.dispersion = 0.5f;
  MediumStack media;
  EXPECT_EQ(media.interface(0, glass, true).etaT, 1.5f);  // no wavelength yet: n_d
  media.setWavelength(450.0f);
  const float n450 = dispersiveIor(1.5f, 0.5f, 450.0f);
  EXPECT_EQ(media.interface(0, glass, true).etaT, n450);
  media.cross(0, glass, true);
  EXPECT_EQ(media.currentIor(), n450);
  EXPECT_EQ(media.interface(0, glass, false).etaI, n450);
  Material plain = glass;
  plain.layers.dispersion = 0;
  EXPECT_EQ(media.interface(1, plain, true).etaT, 1.5f);  // not dispersive: its own IOR
}

}  // namespace
}  // namespace tray

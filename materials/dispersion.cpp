#include "materials/dispersion.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tray {

namespace {

/// Wyman, Sloan & Shirley 2013, "Simple Analytic Approximations to the CIE XYZ Color Matching
/// Functions" (JCGT 2(2)), the multi-lobe piecewise Gaussian fit (their eq. 2).
double lobe(double l, double mu, double s1, double s2) {
  const double t = (l - mu) / (l < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}

/// XYZ -> linear Rec.709 (sRGB primaries, D65 white): IEC 61966-2-1.
Vec3 toRec709(const Vec3& xyz) {
  return {3.2404542f * xyz.x - 1.5371385f * xyz.y - 0.4985314f * xyz.z,
          -0.9692660f * xyz.x + 1.8760108f * xyz.y + 0.0415560f * xyz.z,
          0.0556434f * xyz.x - 0.2040259f * xyz.y + 1.0572252f * xyz.z};
}

constexpr int kBins = int(kWavelengthMax - kWavelengthMin);  // 1 nm each

struct Table {
  std::array<Color, kBins> response;  ///< clamped rbar_c / N_c at the bin's centre
  std::array<float, kBins> pdf;       ///< per nm, constant over the bin
  std::array<float, kBins + 1> cdf;
  Color norm;        ///< N_c of the clamped curves
  Color signedNorm;  ///< N_c of the signed curves
};

const Table& table() {
  static const Table t = [] {
    Table r;
    std::array<Color, kBins> raw;
    Color sum(0.0f), signedSum(0.0f);
    for (int b = 0; b < kBins; ++b) {
      const Vec3 rgb = toRec709(cieXyzFit(kWavelengthMin + float(b) + 0.5f));
      signedSum += rgb;
      raw[size_t(b)] = {std::max(rgb.x, 0.0f), std::max(rgb.y, 0.0f), std::max(rgb.z, 0.0f)};
      sum += raw[size_t(b)];
    }
    r.norm = sum, r.signedNorm = signedSum;
    r.cdf[0] = 0;
    for (int b = 0; b < kBins; ++b) {
      const Color c = raw[size_t(b)] / sum;
      r.response[size_t(b)] = c;
      r.pdf[size_t(b)] = (c.x + c.y + c.z) / 3.0f;
      r.cdf[size_t(b) + 1] = r.cdf[size_t(b)] + r.pdf[size_t(b)];
    }
    for (float& c : r.cdf) c /= r.cdf[kBins];  // 1 up to rounding: exactly 1 at the end
    return r;
  }();
  return t;
}

int binOf(float lambdaNm) {
  return std::clamp(int(std::floor(lambdaNm - kWavelengthMin)), 0, kBins - 1);
}

}  // namespace

Vec3 cieXyzFit(float lambdaNm) {
  const double l = lambdaNm;
  const double x = 1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
                   0.065 * lobe(l, 501.1, 20.4, 26.2);
  const double y = 0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1);
  const double z = 1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8);
  return {float(x), float(y), float(z)};
}

WavelengthSample sampleWavelength(float u) {
  const Table& t = table();
  // The bin whose cdf interval holds u, then uniformly inside it.
  const auto it = std::upper_bound(t.cdf.begin() + 1, t.cdf.end(), u);
  const int b = std::min(int(it - t.cdf.begin()) - 1, kBins - 1);
  const float lo = t.cdf[size_t(b)], width = t.cdf[size_t(b) + 1] - lo;
  // Below 1 by more than a float step at 830 (6e-5): lambda stays inside bin b.
  const float frac = width > 0 ? std::clamp((u - lo) / width, 0.0f, 0.999f) : 0.5f;
  WavelengthSample s;
  s.lambda = kWavelengthMin + float(b) + frac;
  s.pdf = t.pdf[size_t(b)];
  s.weight = t.response[size_t(b)] / s.pdf;
  return s;
}

float wavelengthPdf(float lambdaNm) {
  if (!(lambdaNm >= kWavelengthMin && lambdaNm < kWavelengthMax)) return 0.0f;
  return table().pdf[size_t(binOf(lambdaNm))];
}

Color wavelengthResponse(float lambdaNm) {
  if (!(lambdaNm >= kWavelengthMin && lambdaNm < kWavelengthMax)) return Color(0.0f);
  return table().response[size_t(binOf(lambdaNm))];
}

Color wavelengthResponseSigned(float lambdaNm) {
  const Table& t = table();
  const Vec3 rgb = toRec709(cieXyzFit(kWavelengthMin + float(binOf(lambdaNm)) + 0.5f));
  return {rgb.x / t.signedNorm.x, rgb.y / t.signedNorm.y, rgb.z / t.signedNorm.z};
}

}  // namespace tray

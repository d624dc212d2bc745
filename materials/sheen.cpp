#include "materials/sheen.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tray {

namespace {

/// The paper's fit of the Charlie masking exponent (eq. in §3 of Conty Estevez & Kulla 2017;
/// the coefficients as the KHR_materials_sheen README lists them), interpolated in (1 - a)^2.
float lFit(float x, float a) {
  const float t = (1.0f - a) * (1.0f - a);
  auto mix = [t](float p, float q) { return p + (q - p) * t; };
  const float A = mix(21.5473f, 25.3245f), B = mix(3.82987f, 3.32435f);
  const float C = mix(0.19823f, 0.16801f), Dd = mix(-1.97760f, -1.27393f);
  const float E = mix(-4.32054f, -4.85967f);
  return A / (1.0f + B * std::pow(x, C)) + Dd * x + E;
}

constexpr int kCosBins = 32, kRoughBins = 32;
using AlbedoTable = std::array<float, kCosBins * kRoughBins>;

/// E(cos_o, a) on a grid (cos_o from 0 to 1, a from kMinRoughness to 1) by the midpoint rule
/// over (theta_i, phi_i), phi on [0, pi] doubled (the BRDF is symmetric about the plane of wo).
AlbedoTable integrateAlbedo() {
  AlbedoTable table{};
  constexpr int kTheta = 64, kPhi = 32;
  for (int r = 0; r < kRoughBins; ++r) {
    const float a = CharlieSheen::kMinRoughness +
                    (1.0f - CharlieSheen::kMinRoughness) * float(r) / (kRoughBins - 1);
    const CharlieSheen sheen(a);
    for (int c = 0; c < kCosBins; ++c) {
      const float cosO = std::max(float(c) / (kCosBins - 1), 1e-3f);
      const Vec3 wo(std::sqrt(1.0f - cosO * cosO), 0.0f, cosO);
      double sum = 0;
      for (int i = 0; i < kTheta; ++i) {
        const double theta = (i + 0.5) * (kPi / 2) / kTheta;
        for (int j = 0; j < kPhi; ++j) {
          const double phi = (j + 0.5) * kPi / kPhi;
          const Vec3 wi(float(std::sin(theta) * std::cos(phi)),
                        float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
          sum += sheen.eval(wo, wi) * std::cos(theta) * std::sin(theta);
        }
      }
      table[size_t(r * kCosBins + c)] = float(sum * 2 * (kPi / 2 / kTheta) * (kPi / kPhi));
    }
  }
  return table;
}

}  // namespace

float CharlieSheen::D(float cosH) const {
  const float invA = 1.0f / a_;
  const float sin2 = std::max(0.0f, 1.0f - cosH * cosH);
  return (2.0f + invA) * std::pow(sin2, 0.5f * invA) / (2.0f * kPi);
}

float CharlieSheen::lambda(float cosTheta) const {
  // |cos| of a unit vector can round past 1 (a direction along the normal, renormalised): the
  // fit's pow(1 - c, C) is then NaN. That was the sheen NaN of issue 39, one sample per render.
  const float c = std::min(std::fabs(cosTheta), 1.0f);
  return c < 0.5f ? std::exp(lFit(c, a_)) : std::exp(2.0f * lFit(0.5f, a_) - lFit(1.0f - c, a_));
}

float CharlieSheen::eval(const Vec3& wo, const Vec3& wi) const {
  if (!sameHemisphere(wo, wi)) return 0.0f;
  const float cosO = absCosTheta(wo), cosI = absCosTheta(wi);
  Vec3 h = wo + wi;
  if (cosO == 0 || cosI == 0 || lengthSquared(h) == 0) return 0.0f;
  h = normalize(h);
  const float V = 1.0f / ((1.0f + lambda(cosO) + lambda(cosI)) * 4.0f * cosO * cosI);
  return D(std::fabs(h.z)) * V;
}

float CharlieSheen::albedo(float cosO) const {
  static const AlbedoTable table = integrateAlbedo();  // thread-safe, once, only if used
  const float x = std::clamp(std::fabs(cosO), 0.0f, 1.0f) * (kCosBins - 1);
  const float y = (a_ - kMinRoughness) / (1.0f - kMinRoughness) * (kRoughBins - 1);
  const int x0 = std::min(int(x), kCosBins - 2), y0 = std::min(int(y), kRoughBins - 2);
  const float fx = x - x0, fy = y - y0;
  auto at = [&](int c, int r) { return table[size_t(r * kCosBins + c)]; };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

}  // namespace tray

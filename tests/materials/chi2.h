#pragma once
// Pearson chi-square goodness-of-fit of a direction sampler against its own pdf, as pbrt-v4
// (src/pbrt/util/tests) and Mitsuba 3 (python/mitsuba/chi2.py) test every BSDF: histogram
// many samples over (theta, phi) bins, integrate the pdf over each bin numerically, pool
// sparse bins, and accept if the p-value exceeds the significance level.
#include <cmath>
#include <functional>
#include <vector>

#include "core/math.h"

namespace tray::test {

/// Regularised upper incomplete gamma Q(a, x) (Numerical Recipes 6.2: series below a + 1,
/// continued fraction above).
inline double gammaQ(double a, double x) {
  if (x <= 0) return 1.0;
  const double gln = std::lgamma(a);
  if (x < a + 1) {
    double sum = 1.0 / a, del = sum, ap = a;
    for (int n = 0; n < 10000; ++n) {
      del *= x / ++ap;
      sum += del;
      if (std::fabs(del) < std::fabs(sum) * 1e-15) break;
    }
    return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::fabs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::fabs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    double del = d * c;
    h *= del;
    if (std::fabs(del - 1) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

struct Chi2Result {
  double pValue = 0;
  int dof = 0;
  double statistic = 0;
  double sampledFraction = 0, pdfIntegral = 0;  ///< valid samples / N and integral of the pdf
};

/// sample(u1, u2, uc, wi) returns false for "no sample"; pdf(wi) is the solid-angle density.
inline Chi2Result chi2Test(const std::function<bool(Vec2, float, Vec3&)>& sample,
                           const std::function<float(const Vec3&)>& pdf, int sampleCount,
                           uint64_t seed, int thetaBins = 16, int phiBins = 32) {
  const int bins = thetaBins * phiBins;
  std::vector<double> observed(bins, 0.0), expected(bins, 0.0);
  auto binOf = [&](const Vec3& w) {
    float theta = std::acos(std::clamp(w.z, -1.0f, 1.0f));
    float phi = std::atan2(w.y, w.x);
    if (phi < 0) phi += 2 * kPi;
    int t = std::min(int(theta / kPi * thetaBins), thetaBins - 1);
    int p = std::min(int(phi / (2 * kPi) * phiBins), phiBins - 1);
    return t * phiBins + p;
  };
  // A simple 64-bit LCG + xorshift is enough to drive the sampler independently of TRay's.
  uint64_t state = seed * 6364136223846793005ull + 1442695040888963407ull;
  auto uniform = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    uint64_t z = state ^ (state >> 33);
    return float(z >> 40) * (1.0f / 16777216.0f);
  };
  int valid = 0;
  for (int i = 0; i < sampleCount; ++i) {
    Vec2 u{uniform(), uniform()};
    float uc = uniform();
    Vec3 wi;
    if (!sample(u, uc, wi)) continue;
    ++valid;
    observed[binOf(wi)] += 1;
  }
  // Composite Simpson's rule over each bin in (theta, phi) with the sin(theta) Jacobian.
  const int sub = 24;
  const double dTheta = kPi / thetaBins, dPhi = 2 * kPi / phiBins;
  double integral = 0;
  for (int t = 0; t < thetaBins; ++t)
    for (int p = 0; p < phiBins; ++p) {
      double sum = 0;
      for (int i = 0; i <= sub; ++i)
        for (int j = 0; j <= sub; ++j) {
          double theta = (t + double(i) / sub) * dTheta, phi = (p + double(j) / sub) * dPhi;
          double wi_ = (i == 0 || i == sub) ? 1 : (i % 2 ? 4 : 2);
          double wj = (j == 0 || j == sub) ? 1 : (j % 2 ? 4 : 2);
          Vec3 w(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                 float(std::cos(theta)));
          sum += wi_ * wj * double(pdf(w)) * std::sin(theta);
        }
      double mass = sum * (dTheta / sub / 3) * (dPhi / sub / 3);
      expected[t * phiBins + p] = mass * sampleCount;
      integral += mass;
    }
  // Pool bins expected to hold fewer than 5 samples (the chi-square approximation needs it).
  Chi2Result r;
  double pooledObs = 0, pooledExp = 0;
  int used = 0;
  for (int b = 0; b < bins; ++b) {
    if (expected[b] < 5) {
      pooledObs += observed[b], pooledExp += expected[b];
      continue;
    }
    double d = observed[b] - expected[b];
    r.statistic += d * d / expected[b];
    ++used;
  }
  if (pooledExp >= 5) {
    double d = pooledObs - pooledExp;
    r.statistic += d * d / pooledExp;
    ++used;
  } else if (pooledObs > 20) {
    r.statistic = 1e30;  // samples where the pdf says there are (almost) none
  }
  r.dof = used - 1;
  r.pValue = gammaQ(r.dof / 2.0, r.statistic / 2.0);
  r.sampledFraction = double(valid) / sampleCount;
  r.pdfIntegral = integral;
  return r;
}

}  // namespace tray::test

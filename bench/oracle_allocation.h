#pragma once
// The best any unbiased per-pixel sample allocation can do for relMSE (issue 37; the measured
// bound: docs/bench/adaptive-oracle-2026-12-07.md). relMSE (bench/image_error.cpp) is the mean
// over pixels and channels of (x - r)^2 / (r^2 + 0.01). A pixel mean of n independent samples
// whose count does not depend on their values has E[(x - r)^2] = var / n per channel, so the
// image's expected relMSE is sum_i a_i / n_i / (3 N), with a_i = sum_c var_ic / (r_ic^2 + 0.01)
// the pixel's relative variance of one sample. Minimising it for a budget sum_i n_i = N B
// (Lagrange: a_i / n_i^2 equal for all i) gives n_i proportional to sqrt(a_i), and with the
// bounds min <= n_i <= max, n_i = clamp(lambda sqrt(a_i), min, max) (the KKT conditions of the
// convex problem), lambda chosen so that the budget is spent. Without bounds its gain over
// uniform n_i = B is mean(a) / mean(sqrt(a))^2.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace tray {

/// Samples per pixel n_i = clamp(lambda sqrt(a_i), minSpp, maxSpp) whose mean is meanSpp
/// (clamped to [minSpp, maxSpp]): the allocation that minimises sum a_i / n_i for that budget.
inline std::vector<double> oracleAllocation(std::span<const double> a, double meanSpp,
                                            double minSpp, double maxSpp) {
  meanSpp = std::clamp(meanSpp, minSpp, maxSpp);
  auto allocate = [&](double lambda) {
    std::vector<double> n(a.size());
    for (size_t i = 0; i < a.size(); ++i)
      n[i] = std::clamp(lambda * std::sqrt(std::max(a[i], 0.0)), minSpp, maxSpp);
    return n;
  };
  auto mean = [](const std::vector<double>& n) {
    double s = 0;
    for (double v : n) s += v;
    return n.empty() ? 0 : s / double(n.size());
  };
  // The mean is continuous and non-decreasing in lambda: bisection on a log scale.
  double lo = 0, hi = 1;
  while (mean(allocate(hi)) < meanSpp && hi < 1e30) hi *= 2;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (mean(allocate(mid)) < meanSpp ? lo : hi) = mid;
  }
  return allocate(hi);
}

/// The expected relMSE of an image whose pixel i takes n[i] samples of relative variance a[i]
/// (summed over its 3 channels): sum a_i / n_i / (3 N).
inline double expectedRelMse(std::span<const double> a, std::span<const double> n) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] / n[i];
  return a.empty() ? 0 : s / (3.0 * double(a.size()));
}

/// The gain of the unbounded optimum over uniform sampling at equal samples:
/// mean(a) / mean(sqrt(a))^2 (Cauchy-Schwarz: at least 1, 1 only for equal a).
inline double unboundedGain(std::span<const double> a) {
  double s = 0, r = 0;
  for (double v : a) s += v, r += std::sqrt(std::max(v, 0.0));
  if (a.empty() || r == 0) return 1;
  const double n = double(a.size());
  return (s / n) / ((r / n) * (r / n));
}

/// Whole steps of `step` samples for a real-valued allocation, spending the same total within
/// one step: error diffusion along the pixels (each pixel within one step of its share), at
/// least one step and at most maxSteps each.
inline std::vector<int> wholeSteps(std::span<const double> n, double step, int maxSteps) {
  std::vector<int> k(n.size());
  double carry = 0;
  for (size_t i = 0; i < n.size(); ++i) {
    const double want = n[i] / step + carry;
    k[i] = std::clamp(int(std::lround(want)), 1, maxSteps);
    carry = want - k[i];
  }
  return k;
}

}  // namespace tray

#pragma once
// The best any unbiased per-pixel sample allocation can do for relMSE (issue 37; the measured
// bound: docs/bench/adaptive-oracle-2026-12-07.md). relMSE (bench/image_error.cpp) is the mean
// over pixels and channels of (x - r)^2 / (r^2 + 0.01). A pixel mean of n independent samples
// whose count does not depend on their values has E[(x - r)^2] = var / n per channel, so the
// image's expected relMSE is sum_i a_i / n_i / (3 N), with a_i = sum_c var_ic / (r_ic^2 + 0.01)
// the pixel's relative variance of one sample. Minimising it for a budget sum_i c_i n_i = C,
// c_i the cost of one of pixel i's samples (Lagrange: a_i / n_i^2 = mu c_i for all i) gives
// n_i proportional to sqrt(a_i / c_i), and with the bounds min <= n_i <= max,
// n_i = clamp(lambda sqrt(a_i / c_i), min, max) (the KKT conditions of the convex problem),
// lambda chosen so that the budget is spent. With equal costs (a budget of samples) that is
// n_i proportional to sqrt(a_i), whose gain over uniform n_i = B is mean(a) / mean(sqrt(a))^2;
// with costs, the cost-aware allocation's gain over uniform at equal cost is
// mean(a) mean(c) / mean(sqrt(a c))^2 (docs/bench/adaptive-cost-2026-12-07.md).
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

namespace tray {

/// Samples per pixel n_i = clamp(lambda w_i, minSpp, maxSpp) whose mean cost
/// sum_i c_i n_i / N is meanCost (clamped to what the bounds allow): the allocation of the
/// header comment for w_i = sqrt(a_i / c_i) (costAwareAllocation), or any other weights at
/// that cost (w_i = sqrt(a_i): the cost-blind allocation spending the same budget).
inline std::vector<double> weightedAllocation(std::span<const double> w, std::span<const double> c,
                                              double meanCost, double minSpp, double maxSpp) {
  auto allocate = [&](double lambda) {
    std::vector<double> n(w.size());
    for (size_t i = 0; i < w.size(); ++i)
      n[i] = std::clamp(lambda * std::max(w[i], 0.0), minSpp, maxSpp);
    return n;
  };
  auto cost = [&](const std::vector<double>& n) {
    double s = 0;
    for (size_t i = 0; i < n.size(); ++i) s += c[i] * n[i];
    return n.empty() ? 0 : s / double(n.size());
  };
  meanCost = std::clamp(meanCost, cost(allocate(0)), cost(allocate(1e300)));
  // The cost is continuous and non-decreasing in lambda: bisection on a log scale.
  double lo = 0, hi = 1;
  while (cost(allocate(hi)) < meanCost && hi < 1e30) hi *= 2;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (cost(allocate(mid)) < meanCost ? lo : hi) = mid;
  }
  return allocate(hi);
}

/// n_i = clamp(lambda sqrt(a_i / c_i), minSpp, maxSpp) of mean cost meanCost: the allocation
/// that minimises sum a_i / n_i for the budget sum c_i n_i = N meanCost.
inline std::vector<double> costAwareAllocation(std::span<const double> a,
                                               std::span<const double> c, double meanCost,
                                               double minSpp, double maxSpp) {
  std::vector<double> w(a.size());
  for (size_t i = 0; i < a.size(); ++i) w[i] = std::sqrt(std::max(a[i], 0.0) / c[i]);
  return weightedAllocation(w, c, meanCost, minSpp, maxSpp);
}

/// Samples per pixel n_i = clamp(lambda sqrt(a_i), minSpp, maxSpp) whose mean is meanSpp
/// (clamped to [minSpp, maxSpp]): the allocation that minimises sum a_i / n_i for that budget
/// (every sample costing the same).
inline std::vector<double> oracleAllocation(std::span<const double> a, double meanSpp,
                                            double minSpp, double maxSpp) {
  return costAwareAllocation(a, std::vector<double>(a.size(), 1.0), meanSpp, minSpp, maxSpp);
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

/// The expected relMSE of uniform sampling at the cost of allocation n (sum c_i n_i spread
/// evenly: sum c_i n_i / sum c_j samples per pixel) over that of n: n's gain at equal cost.
inline double gainAtEqualCost(std::span<const double> a, std::span<const double> c,
                              std::span<const double> n) {
  double spent = 0, perSample = 0;
  for (size_t i = 0; i < a.size(); ++i) spent += c[i] * n[i], perSample += c[i];
  const std::vector<double> uniform(a.size(), spent / perSample);
  return expectedRelMse(a, uniform) / expectedRelMse(a, n);
}

/// The gain over uniform sampling at equal cost of the unbounded cost-aware optimum,
/// mean(a) mean(c) / mean(sqrt(a c))^2, or (costBlind) of n proportional to sqrt(a) at that
/// cost, mean(a) mean(c) / (mean(sqrt a) mean(c sqrt a)).
inline double unboundedGainAtEqualCost(std::span<const double> a, std::span<const double> c,
                                       bool costBlind = false) {
  double sa = 0, sc = 0, root = 0, sr = 0, scr = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double r = std::sqrt(std::max(a[i], 0.0));
    sa += a[i], sc += c[i], root += std::sqrt(std::max(a[i], 0.0) * c[i]);
    sr += r, scr += c[i] * r;
  }
  if (a.empty() || root == 0) return 1;
  // Uniform's error x cost is sum a sum c; the cost-aware optimum's (sum sqrt(a c))^2, the
  // cost-blind one's sum sqrt(a) sum c sqrt(a) (Cauchy-Schwarz: each at least the next).
  return sa * sc / (costBlind ? sr * scr : root * root);
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

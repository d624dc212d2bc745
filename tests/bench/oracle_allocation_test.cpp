// The oracle allocation behind bench/adaptive_oracle (bench/oracle_allocation.h) on images
// whose answer is known by hand.
#include "bench/oracle_allocation.h"

#include <gtest/gtest.h>

#include <numeric>
#include <random>

namespace tray {
namespace {

double mean(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

TEST(OracleAllocation, SamplesFollowTheStandardDeviation) {
  // a = 1, 1, 4, 4: sqrt = 1, 1, 2, 2, so at 6 spp on average n = 4, 4, 8, 8.
  const std::vector<double> a{1, 1, 4, 4};
  const std::vector<double> n = oracleAllocation(a, 6, 0, 1e9);
  EXPECT_NEAR(n[0], 4, 1e-6);
  EXPECT_NEAR(n[3], 8, 1e-6);
  // Gain: mean(a) / mean(sqrt a)^2 = 2.5 / 2.25, the ratio of the expected relMSEs.
  const std::vector<double> uniform(4, 6.0);
  EXPECT_NEAR(unboundedGain(a), 2.5 / 2.25, 1e-12);
  EXPECT_NEAR(expectedRelMse(a, uniform) / expectedRelMse(a, n), 2.5 / 2.25, 1e-6);
  // Equal variances: nothing to gain.
  EXPECT_NEAR(unboundedGain(std::vector<double>(5, 3.0)), 1, 1e-12);
}

TEST(OracleAllocation, MinimumSamplesBind) {
  // a = 1, 100 at 2 spp on average, at least 1: unbounded n would be 4/11 and 40/11, so the
  // first is held at 1 and the second takes the rest, 3.
  const std::vector<double> a{1, 100};
  const std::vector<double> n = oracleAllocation(a, 2, 1, 1e9);
  EXPECT_NEAR(n[0], 1, 1e-6);
  EXPECT_NEAR(n[1], 3, 1e-6);
  EXPECT_NEAR(expectedRelMse(a, n), (1.0 / 1 + 100.0 / 3) / 6, 1e-6);
  // The maximum binds the same way; and a budget at the minimum is uniform.
  const std::vector<double> capped = oracleAllocation(a, 2, 0, 2.5);
  EXPECT_NEAR(capped[1], 2.5, 1e-6);
  EXPECT_NEAR(capped[0], 1.5, 1e-6);
  EXPECT_NEAR(oracleAllocation(a, 1, 1, 1e9)[1], 1, 1e-6);
}

TEST(OracleAllocation, NoOtherAllocationDoesBetter) {
  // Random images: random perturbations of the optimum that keep its budget never lower the
  // expected relMSE (the optimum of a convex problem).
  std::mt19937_64 rng(7);
  std::lognormal_distribution<double> heavy(0, 2);
  std::vector<double> a(200);
  for (double& v : a) v = heavy(rng);
  const std::vector<double> best = oracleAllocation(a, 32, 4, 1024);
  EXPECT_NEAR(mean(best), 32, 1e-6);
  const double bestError = expectedRelMse(a, best);
  std::uniform_int_distribution<size_t> pick(0, a.size() - 1);
  for (int t = 0; t < 200; ++t) {
    std::vector<double> n = best;
    const size_t i = pick(rng), j = pick(rng);
    const double move = std::min(n[i] - 4, 1.0);
    n[i] -= move, n[j] += move;
    EXPECT_GE(expectedRelMse(a, n), bestError * (1 - 1e-12));
  }
}

TEST(OracleAllocation, WholeStepsKeepTheBudget) {
  const std::vector<double> n{16, 40, 8, 100, 24};  // 188 samples
  const std::vector<int> k = wholeSteps(n, 16, 1000);
  int total = 0;
  for (size_t i = 0; i < n.size(); ++i) {
    total += k[i];
    EXPECT_GE(k[i], 1);
  }
  EXPECT_NEAR(total * 16, 188, 16);
}

}  // namespace
}  // namespace tray

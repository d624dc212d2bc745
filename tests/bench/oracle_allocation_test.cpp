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

TEST(OracleAllocation, CostAwareSamplesFollowSqrtOfVarianceOverCost) {
  // a = 1, 4 with costs c = 1, 4: sqrt(a / c) = 1, 1, so at a mean cost of 5 per pixel
  // (sum c n = 10) n = 2, 2, which is uniform's at that cost: when the variance grows as the
  // cost, uniform sampling is already optimal (gain 1). The cost-blind n proportional to
  // sqrt(a) = 1, 2 spends the same 10 as n = 10/9, 20/9, and loses: sum a / n = 0.9 + 1.8 =
  // 2.7 against 2.5, a gain of 25/27.
  const std::vector<double> a{1, 4}, c{1, 4};
  const std::vector<double> n = costAwareAllocation(a, c, 5, 0, 1e9);
  EXPECT_NEAR(n[0], 2, 1e-6);
  EXPECT_NEAR(n[1], 2, 1e-6);
  EXPECT_NEAR(gainAtEqualCost(a, c, n), 1, 1e-6);
  EXPECT_NEAR(unboundedGainAtEqualCost(a, c), 1, 1e-12);
  const std::vector<double> rootA{1, 2};
  const std::vector<double> blind = weightedAllocation(rootA, c, 5, 0, 1e9);
  EXPECT_NEAR(blind[0], 10.0 / 9, 1e-6);
  EXPECT_NEAR(blind[1], 20.0 / 9, 1e-6);
  EXPECT_NEAR(gainAtEqualCost(a, c, blind), 25.0 / 27, 1e-6);
  EXPECT_NEAR(unboundedGainAtEqualCost(a, c, true), 25.0 / 27, 1e-12);
  // Equal costs: the cost-aware allocation is the cost-blind one.
  const std::vector<double> ones(2, 3.0);
  const std::vector<double> same = costAwareAllocation(a, ones, 3 * 6, 0, 1e9);
  const std::vector<double> oracle = oracleAllocation(a, 6, 0, 1e9);
  EXPECT_NEAR(same[0], oracle[0], 1e-6);
  EXPECT_NEAR(same[1], oracle[1], 1e-6);
}

TEST(OracleAllocation, CostAwareBeatsCostBlindAtEqualCost) {
  // a = 4, 4 with costs 1, 9: sqrt(a / c) = 2, 2/3, so at sum c n = 20, n = 5, 5/3 (cost
  // 5 + 15); error 4/5 + 12/5 = 3.2. Cost-blind n = 2, 2 (cost 20): error 4. Gain 1.25, and
  // over uniform (also n = 2, 2 here) the same; unbounded: mean(a) mean(c) / mean(sqrt(ac))^2
  // = 4 x 5 / 4^2 = 1.25.
  const std::vector<double> a{4, 4}, c{1, 9};
  const std::vector<double> n = costAwareAllocation(a, c, 10, 0, 1e9);
  EXPECT_NEAR(n[0], 5, 1e-6);
  EXPECT_NEAR(n[1], 5.0 / 3, 1e-6);
  EXPECT_NEAR(gainAtEqualCost(a, c, n), 1.25, 1e-6);
  EXPECT_NEAR(unboundedGainAtEqualCost(a, c), 1.25, 1e-12);
  EXPECT_NEAR(unboundedGainAtEqualCost(a, c, true), 1, 1e-12);
  // No budget-keeping move of samples between the two lowers its error (the optimum).
  for (double move : {-0.5, -0.1, 0.1, 0.5}) {
    const std::vector<double> m{n[0] + move * 9, n[1] - move};
    EXPECT_GT(expectedRelMse(a, m), expectedRelMse(a, n));
  }
}

}  // namespace
}  // namespace tray

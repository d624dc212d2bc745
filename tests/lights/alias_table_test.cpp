#include "lights/alias_table.h"

#include <gtest/gtest.h>

namespace tray {
namespace {

TEST(AliasTable, PicksEachIndexInProportionToItsWeight) {
  const std::vector<float> w = {1, 0, 3, 0.5f, 10, 2.5f};
  AliasTable table(w);
  double total = 17;
  std::vector<int> counts(w.size(), 0);
  const int n = 1'000'000;
  for (int i = 0; i < n; ++i) {
    float pmf;
    uint32_t k = table.sample((i + 0.5f) / n, pmf);
    ASSERT_LT(k, w.size());
    EXPECT_FLOAT_EQ(pmf, float(w[k] / total));
    ++counts[k];
  }
  // Stratified u: the counts are exact up to the bin edges.
  for (size_t k = 0; k < w.size(); ++k) EXPECT_NEAR(counts[k] / double(n), w[k] / total, 1e-4);
  EXPECT_EQ(counts[1], 0);
}

TEST(AliasTable, AllZeroWeightsSampleNothing) {
  EXPECT_TRUE(AliasTable({0, 0}).empty());
  EXPECT_TRUE(AliasTable(std::vector<float>{}).empty());
  EXPECT_EQ(AliasTable({0, 2}).pmf(1), 1.0f);
}

}  // namespace
}  // namespace tray

// Tree invariants of both builders: every primitive in exactly one leaf, boxes enclose their
// contents, unusable bounds left out; and SAH cost comparisons between the builders.
#include <gtest/gtest.h>

#include <random>

#include "accel/bvh.h"
#include "tests/accel/random_boxes.h"

namespace tray {
namespace {

using tray::test::randomBoxes;

bool contains(const Bounds3& outer, const Bounds3& inner) {
  for (int a = 0; a < 3; ++a)
    if (inner.lo[a] < outer.lo[a] || inner.hi[a] > outer.hi[a]) return false;
  return true;
}

/// Walks the tree; checks containment and returns how often each primitive appears.
std::vector<int> checkTree(const Bvh& bvh, const std::vector<Bounds3>& boxes, int& depth) {
  std::vector<int> seen(boxes.size(), 0);
  std::vector<std::pair<uint32_t, int>> stack{{0u, 0}};
  depth = 0;
  while (!stack.empty()) {
    auto [i, d] = stack.back();
    stack.pop_back();
    depth = std::max(depth, d);
    const BvhNode& n = bvh.nodes[i];
    if (n.leaf()) {
      for (uint32_t k = n.offset; k < n.offset + n.count; ++k) {
        uint32_t id = bvh.primitives[k];
        ++seen[id];
        EXPECT_TRUE(contains(n.bounds(), boxes[id]));
      }
      continue;
    }
    for (uint32_t c : {n.offset, n.offset + 1}) {
      EXPECT_LT(c, bvh.nodes.size());
      EXPECT_TRUE(contains(n.bounds(), bvh.nodes[c].bounds()));
      stack.push_back({c, d + 1});
    }
  }
  return seen;
}

class BvhBuild : public ::testing::TestWithParam<BvhBuilder> {};

TEST_P(BvhBuild, EveryPrimitiveInExactlyOneLeafInsideItsBoxes) {
  BvhBuildOptions opt;
  opt.builder = GetParam();
  for (int n : {1, 2, 7, 1000, 50000}) {
    auto boxes = randomBoxes(uint32_t(n), n);
    Bvh bvh = buildBvh(boxes, opt);
    int depth = 0;
    auto seen = checkTree(bvh, boxes, depth);
    for (int c : seen) ASSERT_EQ(c, 1) << n;
    EXPECT_LT(depth, 256);
  }
}

TEST_P(BvhBuild, UnusableBoundsAreLeftOutAndCoincidentCentroidsStillSplit) {
  BvhBuildOptions opt;
  opt.builder = GetParam();
  std::vector<Bounds3> boxes(300, Bounds3{{0, 0, 0}, {1, 1, 1}});  // all centroids equal
  boxes[5] = Bounds3();                                            // empty
  boxes[6] = Bounds3{{-kInfinity, 0, 0}, {kInfinity, 1, 1}};       // infinite
  Bvh bvh = buildBvh(boxes, opt);
  int depth = 0;
  auto seen = checkTree(bvh, boxes, depth);
  for (size_t i = 0; i < boxes.size(); ++i) EXPECT_EQ(seen[i], i == 5 || i == 6 ? 0 : 1) << i;
  for (const BvhNode& n : bvh.nodes) EXPECT_LE(n.count, std::max(opt.maxLeafSize, 1));
  EXPECT_TRUE(buildBvh({}, opt).nodes.empty());
}

TEST(BvhBuildDepth, BelowTheSahDepthSplitsAreMediansThatBoundTheDepth) {
  // The guard that keeps any input under the traversal stacks' 256 levels, tried at depth 2:
  // below it every split halves its range, so depth <= 2 + ceil(log2(n)).
  auto boxes = randomBoxes(5, 50000);
  BvhBuildOptions opt;
  opt.sahDepth = 2;
  Bvh bvh = buildBvh(boxes, opt);
  int depth = 0;
  auto seen = checkTree(bvh, boxes, depth);
  for (int c : seen) ASSERT_EQ(c, 1);
  EXPECT_LE(depth, 2 + 16);  // 2^16 > 50000
  // Medians, not SAH: a worse tree than the default's.
  EXPECT_GT(sahCost(bvh, opt), sahCost(buildBvh(boxes, BvhBuildOptions{}), opt));
}

INSTANTIATE_TEST_SUITE_P(Builders, BvhBuild,
                         ::testing::Values(BvhBuilder::kBinnedSah, BvhBuilder::kGoldsmithSalmon),
                         [](const auto& info) {
                           return info.param == BvhBuilder::kBinnedSah ? "sah" : "gs";
                         });

TEST(BvhSahCost, BinnedSahBeatsGoldsmithSalmonAndRepeatsExactly) {
  auto boxes = randomBoxes(99, 20000);
  BvhBuildOptions sah, gs;
  gs.builder = BvhBuilder::kGoldsmithSalmon;
  double costSah = sahCost(buildBvh(boxes, sah), sah);
  double costGs = sahCost(buildBvh(boxes, gs), gs);
  std::printf("SAH cost, 20k boxes: binned SAH %.2f, Goldsmith-Salmon %.2f\n", costSah, costGs);
  EXPECT_LT(costSah, costGs);
  // The parallel build may number nodes differently (so the sum runs in another order), but the
  // tree is the same.
  EXPECT_NEAR(costSah, sahCost(buildBvh(boxes, sah), sah), 1e-9 * costSah);
  EXPECT_DOUBLE_EQ(costGs, sahCost(buildBvh(boxes, gs), gs));
}

TEST(BvhSahCost, MatchesHandComputedTwoLeafTree) {
  // Two unit boxes 2 apart: root box 4x1x1 has area 18, each leaf 6, one primitive each.
  std::vector<Bounds3> boxes{{{0, 0, 0}, {1, 1, 1}}, {{3, 0, 0}, {4, 1, 1}}};
  BvhBuildOptions opt;
  opt.maxLeafSize = 1;
  Bvh bvh = buildBvh(boxes, opt);
  ASSERT_EQ(bvh.nodes.size(), 3u);
  double root = Bounds3{{0, 0, 0}, {4, 1, 1}}.surfaceArea();  // 18
  EXPECT_NEAR(sahCost(bvh, opt), 1.0 + 2 * 6.0 / root, 1e-9);
}

}  // namespace
}  // namespace tray

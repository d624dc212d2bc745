// The 4-wide layout: collapsing keeps every primitive in exactly one leaf inside its boxes,
// traversal visits leaves front to back for either ray direction, and the four-lane triangle
// test is bit-for-bit the scalar watertight test (so the Embree comparisons carry over).
#include "accel/bvh4.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "accel/bvh4_traversal.h"
#include "accel/bvh_triangle4.h"
#include "tests/accel/random_boxes.h"

namespace tray {
namespace {

using tray::test::randomBoxes;

Bounds3 slot(const Bvh4Node& n, int c) {
  return {{n.lo[0][c], n.lo[1][c], n.lo[2][c]}, {n.hi[0][c], n.hi[1][c], n.hi[2][c]}};
}

bool contains(const Bounds3& outer, const Bounds3& inner) {
  for (int a = 0; a < 3; ++a)
    if (inner.lo[a] < outer.lo[a] || inner.hi[a] > outer.hi[a]) return false;
  return true;
}

class Bvh4Collapse : public ::testing::TestWithParam<BvhBuilder> {};

TEST_P(Bvh4Collapse, EveryPrimitiveInExactlyOneLeafInsideItsBoxes) {
  BvhBuildOptions opt;
  opt.builder = GetParam();
  for (int n : {1, 2, 5, 1000, 30000}) {
    auto boxes = randomBoxes(uint32_t(n) + 7, n);
    Bvh binary = buildBvh(boxes, opt);
    size_t binaryLeaves = 0;
    for (const BvhNode& b : binary.nodes) binaryLeaves += b.leaf();
    Bvh4 bvh = collapseToBvh4(binary);
    ASSERT_FALSE(bvh.nodes.empty());
    EXPECT_LT(bvh.nodes.size(), binary.nodes.size() / 2 + 2) << n;  // wide nodes: fewer
    std::vector<int> seen(boxes.size(), 0);
    size_t leaves = 0;
    std::vector<uint32_t> stack{0};
    while (!stack.empty()) {
      const Bvh4Node& node = bvh.nodes[stack.back()];
      stack.pop_back();
      int used = 0;
      for (int c = 0; c < 4; ++c) {
        uint32_t ref = node.child[c];
        if (ref == bvh4ref::kEmpty) {
          EXPECT_TRUE(slot(node, c).empty());
          continue;
        }
        ++used;
        if (!bvh4ref::leaf(ref)) {
          ASSERT_LT(ref, bvh.nodes.size());
          for (int g = 0; g < 4; ++g) {
            if (bvh.nodes[ref].child[g] == bvh4ref::kEmpty) continue;
            EXPECT_TRUE(contains(slot(node, c), slot(bvh.nodes[ref], g)));
          }
          stack.push_back(ref);
          continue;
        }
        ++leaves;
        for (uint32_t k = 0; k < bvh4ref::count(ref); ++k) {
          uint32_t id = bvh.primitives[bvh4ref::first(ref) + k];
          ++seen[id];
          EXPECT_TRUE(contains(slot(node, c), boxes[id]));
        }
      }
      EXPECT_GE(used, 1);
    }
    EXPECT_EQ(leaves, binaryLeaves) << n;
    for (int c : seen) ASSERT_EQ(c, 1) << n;
  }
  EXPECT_TRUE(collapseToBvh4(Bvh{}).nodes.empty());
}

INSTANTIATE_TEST_SUITE_P(Builders, Bvh4Collapse,
                         ::testing::Values(BvhBuilder::kBinnedSah, BvhBuilder::kGoldsmithSalmon),
                         [](const auto& info) {
                           return info.param == BvhBuilder::kBinnedSah ? "sah" : "gs";
                         });

TEST(Bvh4Traversal, VisitsLeavesFrontToBackAndPrunesBehindAHit) {
  // A row of 64 unit boxes along x, one per leaf.
  std::vector<Bounds3> boxes;
  for (int i = 0; i < 64; ++i) boxes.push_back({{2.0f * i, 0, 0}, {2.0f * i + 1, 1, 1}});
  BvhBuildOptions opt;
  opt.maxLeafSize = 1;
  Bvh4 bvh = collapseToBvh4(buildBvh(boxes, opt));
  for (float dir : {1.0f, -1.0f}) {
    Vec3 o{dir > 0 ? -1.0f : 130.0f, 0.5f, 0.5f};
    Bvh4Ray r = prepareBvh4Ray(o, {dir, 0.0f, 0.0f});
    std::vector<uint32_t> order;
    float tmax = kInfinity;
    traverseBvh4(bvh, r, 0.0f, tmax, [&](uint32_t first, uint32_t) {
      order.push_back(bvh.primitives[first]);
      return false;
    });
    ASSERT_EQ(order.size(), 64u) << dir;
    for (size_t i = 1; i < order.size(); ++i)
      EXPECT_EQ(int(order[i]) - int(order[i - 1]), dir > 0 ? 1 : -1) << dir;
    // Closest-hit style: a "hit" in the first leaf lowers tmax; no farther leaf is visited.
    order.clear();
    tmax = kInfinity;
    traverseBvh4(bvh, r, 0.0f, tmax, [&](uint32_t first, uint32_t) {
      order.push_back(bvh.primitives[first]);
      tmax = 1.5f;
      return false;
    });
    EXPECT_EQ(order.size(), 1u) << dir;
  }
}

TEST(Triangle4, LanesAreBitForBitTheScalarWatertightTest) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int hits = 0, edgeRays = 0;
  for (int i = 0; i < 20000; ++i) {
    Triangle4 block;
    Vec3 p[4][3];
    const int used = 1 + i % 4;  // partly filled blocks too
    for (int lane = 0; lane < 4; ++lane)
      for (int v = 0; v < 3; ++v) {
        p[lane][v] = lane < used ? Vec3(u(rng), u(rng), u(rng)) : Vec3(NAN);
        for (int a = 0; a < 3; ++a) block.p[v][a][lane] = p[lane][v][a];
      }
    // Some rays exactly through a vertex or along grid values, where edge values are zero.
    Vec3 o{3 * u(rng), 3 * u(rng), 3 * u(rng)};
    Vec3 target = i % 5 == 0 ? p[0][i % 3] : Vec3(u(rng), u(rng), u(rng));
    if (i % 7 == 0) o = {target.x, target.y, 3.0f};  // axis-aligned
    edgeRays += i % 5 == 0 || i % 7 == 0;
    Vec3 d = target - o;
    float tmax = i % 3 == 0 ? 2.0f * u(rng) + 2.0f : kInfinity;
    WatertightRay4 r = prepareWatertight4(o, d);
    alignas(16) float t[4], b1[4], b2[4];
    int mask = intersectWatertight4(r, block, 0.0f, tmax, t, b1, b2);
    for (int lane = 0; lane < 4; ++lane) {
      float ts = 0, b1s = 0, b2s = 0;
      bool hit = lane < used && intersectWatertight(prepareWatertight(o, d), p[lane][0], p[lane][1],
                                                    p[lane][2], 0.0f, tmax, ts, b1s, b2s);
      ASSERT_EQ(hit, bool(mask & (1 << lane))) << i << " " << lane;
      if (!hit) continue;
      ++hits;
      EXPECT_EQ(std::memcmp(&ts, &t[lane], 4), 0) << i;
      EXPECT_EQ(std::memcmp(&b1s, &b1[lane], 4), 0) << i;
      EXPECT_EQ(std::memcmp(&b2s, &b2[lane], 4), 0) << i;
    }
  }
  EXPECT_GT(hits, 2000);
  EXPECT_GT(edgeRays, 5000);
}

}  // namespace
}  // namespace tray

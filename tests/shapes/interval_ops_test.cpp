#include "shapes/interval_ops.h"

#include <gtest/gtest.h>

namespace tray {
namespace {

/// An interval [a, b] whose crossings carry a material tag (to see whose surface is reported)
/// and outward normals along -x at the entry, +x at the exit (a ray running along +x).
Interval span(float a, float b, int tag = 0) {
  return {{a, {-1, 0, 0}, {}, tag}, {b, {1, 0, 0}, {}, tag}};
}

using Spans = std::vector<Interval>;
const TieTolerance kExact{};  // no merging of nearby boundaries

Spans combine(CsgOp op, std::vector<Spans> operands, TieTolerance tol = kExact) {
  Spans out;
  combineIntervals(op, operands, tol, out);
  return out;
}

/// The result as flat [enter, exit, enter, exit, ...] for compact comparisons.
std::vector<float> ends(const Spans& s) {
  std::vector<float> v;
  for (const Interval& i : s) v.insert(v.end(), {i.enter.t, i.exit.t});
  return v;
}

using V = std::vector<float>;
constexpr float inf = kInfinity;

TEST(IntervalOps, UnionMergesOverlapsAndKeepsGaps) {
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{span(0, 2), span(5, 6)}, {span(1, 3)}})),
            V({0, 3, 5, 6}));
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{span(0, 1)}, {span(2, 3)}, {span(0.5f, 2.5f)}})),
            V({0, 3}));
}

TEST(IntervalOps, IntersectionKeepsCommonPart) {
  EXPECT_EQ(ends(combine(CsgOp::kIntersection, {{span(0, 2), span(5, 8)}, {span(1, 6)}})),
            V({1, 2, 5, 6}));
  EXPECT_EQ(ends(combine(CsgOp::kIntersection, {{span(0, 4)}, {span(1, 5)}, {span(-1, 3)}})),
            V({1, 3}));
}

TEST(IntervalOps, DifferenceIsFirstMinusAllOthers) {
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(0, 10)}, {span(2, 3)}, {span(5, 12)}})),
            V({0, 2, 3, 5}));
  // The subtracted surfaces face the other way: their normals are flipped in the result.
  Spans r = combine(CsgOp::kDifference, {{span(0, 10, 1)}, {span(2, 3, 2)}});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].exit.material, 2);
  EXPECT_EQ(r[0].exit.normal, Vec3(1, 0, 0));  // entering the hole = leaving the result
  EXPECT_EQ(r[1].enter.material, 2);
  EXPECT_EQ(r[1].enter.normal, Vec3(-1, 0, 0));
  EXPECT_EQ(r[1].exit.material, 1);
}

TEST(IntervalOps, EmptyOperands) {
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{}, {span(1, 2)}})), V({1, 2}));
  EXPECT_TRUE(combine(CsgOp::kIntersection, {{span(0, 1)}, {}}).empty());
  EXPECT_TRUE(combine(CsgOp::kDifference, {{}, {span(0, 1)}}).empty());
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(0, 1)}, {}})), V({0, 1}));
  EXPECT_TRUE(combine(CsgOp::kIntersection, {{span(0, 1)}, {span(2, 3)}}).empty());
  EXPECT_TRUE(combine(CsgOp::kUnion, {}).empty());
}

TEST(IntervalOps, TouchingIntervalsMergeOrVanish) {
  // Exactly touching: one solid, no inner surface.
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{span(0, 1)}, {span(1, 2)}})), V({0, 2}));
  // Touching only at a point: intersection is empty, nothing is reported.
  EXPECT_TRUE(combine(CsgOp::kIntersection, {{span(0, 1)}, {span(1, 2)}}).empty());
  // A subtracted solid flush with the first one's end: no sliver left behind.
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(0, 2)}, {span(1, 2)}})), V({0, 1}));
}

TEST(IntervalOps, BoundariesWithinToleranceAreOneEvent) {
  const TieTolerance tol{1e-5f, 1.0f};  // 1e-5 at t = 0, 3e-5 at t = 2
  // Float noise: the subtracted face lands a hair after the first solid's face.
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(0, 2)}, {span(1, 2.00001f)}}, kExact)).size(),
            2u);
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(0, 2.00001f)}, {span(1, 2)}}, kExact)).size(),
            4u);
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(0, 2.00001f)}, {span(1, 2)}}, tol)), V({0, 1}));
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(0, 2)}, {span(0.99999f, 3)}}, tol)).size(), 2u);
  // Subtracted entry a hair before the first solid's entry: the face is removed either way.
  EXPECT_TRUE(combine(CsgOp::kDifference, {{span(1.00001f, 2)}, {span(1, 2)}}, tol).empty());
  EXPECT_TRUE(combine(CsgOp::kDifference, {{span(1, 2)}, {span(1.00001f, 2)}}, tol).empty());
  // A near-gap in a union closes.
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{span(0, 1)}, {span(1.00001f, 2)}}, tol)), V({0, 2}));
  // A thin chord through one solid (a ray grazing a corner) is real and stays, whatever its
  // neighbours: the tolerance only orders boundaries of different operands.
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(1, 1.000001f)}, {span(5, 6)}}, tol)),
            V({1, 1.000001f}));
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{span(1, 1.000001f)}, {}}, tol)), V({1, 1.000001f}));
  EXPECT_EQ(ends(combine(CsgOp::kIntersection, {{span(1, 1.000001f)}, {span(0, 2)}}, tol)),
            V({1, 1.000001f}));
  // Real features larger than the tolerance stay.
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{span(0, 1)}, {span(1.001f, 2)}}, tol)).size(), 4u);
}

TEST(IntervalOps, SurfacesMeetingAtAnAngleAreNotTied) {
  // Issue 18: a ray passing a hair inside the edge where faces of two operands meet at an
  // angle crosses them closer than the tolerance; their order is the geometry, not rounding.
  const TieTolerance tol{1e-5f, 1.0f};  // 1e-5 at t = 0, 2e-5 at t = 1
  const Vec3 x{1, 0, 0}, y{0, 1, 0};
  auto spanN = [](float a, float b, Vec3 na, Vec3 nb, int tag) {
    return Interval{{a, -1.0f * na, {}, tag}, {b, nb, {}, tag}};
  };
  // Intersection: the result starts at the later entry, on that operand's face.
  Spans i = combine(CsgOp::kIntersection,
                    {{spanN(1, 2, x, x, 1)}, {spanN(1.000005f, 3, y, y, 2)}}, tol);
  ASSERT_EQ(i.size(), 1u);
  EXPECT_EQ(i[0].enter.t, 1.000005f);
  EXPECT_EQ(i[0].enter.material, 2);
  // Union: the earlier entry, whichever operand.
  Spans u = combine(CsgOp::kUnion, {{spanN(1.000005f, 2, x, x, 1)}, {spanN(1, 3, y, y, 2)}}, tol);
  ASSERT_EQ(u.size(), 1u);
  EXPECT_EQ(u[0].enter.t, 1.0f);
  EXPECT_EQ(u[0].enter.material, 2);
  // Difference: the thin chord left between the hole's exit and the solid's exit stays, and so
  // does the one before the hole's entry.
  EXPECT_EQ(ends(combine(CsgOp::kDifference,
                         {{spanN(0, 1.000005f, x, x, 1)}, {spanN(0.5f, 1, y, y, 2)}}, tol)),
            V({0, 0.5f, 1, 1.000005f}));
  EXPECT_EQ(ends(combine(CsgOp::kDifference,
                         {{spanN(1, 2, x, x, 1)}, {spanN(1.000005f, 3, y, y, 2)}}, tol)),
            V({1, 1.000005f}));
  // The same boundaries on parallel faces (a shared face computed twice) are tied as before.
  EXPECT_TRUE(combine(CsgOp::kDifference,
                      {{spanN(1, 2, x, x, 1)}, {spanN(1.000005f, 3, x, x, 2)}}, tol)
                  .empty());
  EXPECT_EQ(ends(combine(CsgOp::kDifference,
                         {{spanN(0, 1.000005f, x, x, 1)}, {spanN(0.5f, 1, x, -1.0f * x, 2)}},
                         tol)),
            V({0, 0.5f}));
}

TEST(IntervalOps, SharedFaceReportsTheLowestOperand) {
  // Two solids entered at the same t: the first child's surface (its material) is reported.
  Spans u = combine(CsgOp::kUnion, {{span(0, 1, 7)}, {span(0, 2, 8)}});
  ASSERT_EQ(u.size(), 1u);
  EXPECT_EQ(u[0].enter.material, 7);
  EXPECT_EQ(u[0].exit.material, 8);
  Spans swapped = combine(CsgOp::kUnion, {{span(0, 2, 8)}, {span(0, 1, 7)}});
  EXPECT_EQ(swapped[0].enter.material, 8);
  // A subtracted solid touching from outside: the first solid's face, not the hole's.
  Spans d = combine(CsgOp::kDifference, {{span(1, 2, 1)}, {span(0, 1, 2)}});
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].enter.material, 1);
  EXPECT_EQ(d[0].enter.normal, Vec3(-1, 0, 0));
}

TEST(IntervalOps, NestedAndOverlappingWithinOneOperand) {
  // One operand may hold overlapping or touching intervals (e.g. a mesh's own pieces).
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{span(0, 5), span(1, 2), span(5, 6)}})), V({0, 6}));
  EXPECT_EQ(ends(combine(CsgOp::kIntersection, {{span(0, 3), span(2, 6)}, {span(1, 4)}})),
            V({1, 4}));
  // A solid inside a solid: union is the outer, difference leaves a shell.
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{span(0, 10)}, {span(3, 4)}})), V({0, 10}));
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(0, 10)}, {span(3, 4)}})), V({0, 3, 4, 10}));
  EXPECT_TRUE(combine(CsgOp::kDifference, {{span(3, 4)}, {span(0, 10)}}).empty());
  // Nesting results as operands: (A - B) u C.
  Spans aMinusB = combine(CsgOp::kDifference, {{span(0, 10)}, {span(3, 4)}});
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {aMinusB, {span(2, 5)}})), V({0, 10}));
}

TEST(IntervalOps, InfiniteEndsFromHalfSpaces) {
  Interval below = span(-inf, 0), above = span(0, inf);
  EXPECT_EQ(ends(combine(CsgOp::kIntersection, {{below}, {span(-1, 1)}})), V({-1, 0}));
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{below}, {span(-1, 1)}})), V({-inf, 1}));
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(-inf, inf)}, {span(0, 1)}})),
            V({-inf, 0, 1, inf}));
  EXPECT_EQ(ends(combine(CsgOp::kDifference, {{span(-1, 1)}, {above}})), V({-1, 0}));
  EXPECT_TRUE(combine(CsgOp::kIntersection, {{below}, {span(1, inf)}}).empty());
  EXPECT_EQ(ends(combine(CsgOp::kIntersection, {{span(-inf, 5)}, {span(-inf, 3)}})), V({-inf, 3}));
  // Infinite ends do not absorb finite ones through the tolerance.
  EXPECT_EQ(ends(combine(CsgOp::kUnion, {{below}, {span(1, inf)}}, {1e-5f, 1.0f})),
            V({-inf, 0, 1, inf}));
}

TEST(IntervalOps, ResultIsSortedAndDisjoint) {
  // Many operands with interleaved intervals: the result must be strictly increasing.
  std::vector<Spans> ops;
  for (int k = 0; k < 5; ++k) {
    Spans s;
    for (int i = 0; i < 6; ++i) s.push_back(span(float(k + 7 * i), float(k + 7 * i) + 2.5f));
    ops.push_back(s);
  }
  for (CsgOp op : {CsgOp::kUnion, CsgOp::kIntersection, CsgOp::kDifference}) {
    std::vector<float> e = ends(combine(op, ops));
    for (size_t i = 1; i < e.size(); ++i) EXPECT_LT(e[i - 1], e[i]) << int(op);
  }
  EXPECT_EQ(ends(combine(CsgOp::kUnion, ops)).size(), 12u);  // [7i, 7i + 6.5]
  EXPECT_EQ(ends(combine(CsgOp::kDifference, ops)),
            V({0, 1, 7, 8, 14, 15, 21, 22, 28, 29, 35, 36}));
}

}  // namespace
}  // namespace tray

#pragma once
#include <vector>

#include "core/shape.h"

namespace tray {

/// The boolean operations of constructive solid geometry. Difference is the first operand
/// minus all the others.
enum class CsgOp { kUnion, kIntersection, kDifference };

/// When two boundaries along a ray count as the same point. Boundaries computed through
/// different transforms differ by a few float ULPs even where the surfaces coincide exactly;
/// treating them as one event (and deciding the result from the state after all of them) is
/// what keeps coincident faces free of speckle. The tolerance grows with the magnitude of the
/// point, like float error does: tol(t) = relative * (originScale + |t|), where originScale is
/// |o| / |d| of the ray (both in the space the intervals were computed in).
struct TieTolerance {
  float relative = 0.0f;
  float originScale = 0.0f;
  float at(float t) const { return relative * (originScale + std::fabs(t)); }
};

/// Combines the sorted interval lists of the operands (one list per child solid, each sorted
/// by t; overlapping or touching intervals within one list are allowed) into the sorted,
/// disjoint intervals of the result, in one sweep over all boundaries in t order.
///
/// Rules, so that every ray sees one consistent solid:
/// - Boundaries closer than the tolerance are tied when they can be the same surface: their
///   normals are parallel (the same or opposite way; sine of the angle <= 1e-3), as on a face
///   shared by two children. Boundaries of surfaces meeting at an angle (a ray passing near
///   the edge where they meet) are never tied: their computed order is kept, so no band as
///   wide as the tolerance is cut off or added along such edges (issue 18).
/// - Within a tie each operand's own boundaries keep their order (a thin chord through one
///   child stays), while boundaries of different operands are ordered by the operation: a
///   union takes entries first (touching solids merge, no inner face), an intersection and a
///   difference take exits from the result first (no slivers; a subtracted face flush with
///   the first solid's face removes that face: the subtracted solid wins).
/// - Each result boundary reports the crossing of the lowest-indexed operand among the
///   boundaries tied with the one that made it, pushing the result the same way
///   (deterministic material on shared faces; elsewhere the surface actually crossed).
/// - Crossings of subtracted operands have their normal flipped: the result's outward normal
///   there points into the subtracted solid.
/// `out` is overwritten. Infinite ends (half-spaces) are kept as infinite ends.
void combineIntervals(CsgOp op, const std::vector<std::vector<Interval>>& operands,
                      const TieTolerance& tolerance, std::vector<Interval>& out);

}  // namespace tray

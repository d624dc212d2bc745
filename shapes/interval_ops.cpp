#include "shapes/interval_ops.h"

#include <algorithm>
#include <limits>

namespace tray {
namespace {

/// One boundary of one operand: the ray enters or leaves that operand's solid.
struct Event {
  float t;
  int operand;
  bool entering;
  const Crossing* crossing;
  float key = 0;  ///< t, or the t of the earlier boundary it is tied to (same surface)
};

/// Largest sine of the angle between the normals of two boundaries that can be one surface.
constexpr double kParallelSine = 1e-3;

/// Can two boundaries be the same surface? Coincident surfaces (a shared face, a notch flush
/// with a side) have parallel normals, the same or opposite way. Surfaces that meet at an
/// angle only come close along rays passing near the edge where they meet, and there their
/// order along the ray is the geometry: merging them would cut a band as wide as the tolerance
/// off every such edge (issue 18).
bool sameSurface(const Crossing& a, const Crossing& b) {
  const Vec3 &n = a.normal, &m = b.normal;
  double nn = double(n.x) * n.x + double(n.y) * n.y + double(n.z) * n.z;
  double mm = double(m.x) * m.x + double(m.y) * m.y + double(m.z) * m.z;
  if (nn == 0 || mm == 0) return true;  // no normal to tell: treat as one surface
  double cx = double(n.y) * m.z - double(n.z) * m.y, cy = double(n.z) * m.x - double(n.x) * m.z,
         cz = double(n.x) * m.y - double(n.y) * m.x;
  return cx * cx + cy * cy + cz * cz <= kParallelSine * kParallelSine * nn * mm;
}

/// Is the result inside, given how many intervals of each operand the point lies in?
bool insideResult(CsgOp op, const std::vector<int>& depth) {
  switch (op) {
    case CsgOp::kUnion:
      return std::any_of(depth.begin(), depth.end(), [](int d) { return d > 0; });
    case CsgOp::kIntersection:
      return std::all_of(depth.begin(), depth.end(), [](int d) { return d > 0; });
    case CsgOp::kDifference:
      return depth[0] > 0 &&
             std::all_of(depth.begin() + 1, depth.end(), [](int d) { return d <= 0; });
  }
  return false;
}

/// Does the event push the result inwards? Every operation is monotone in each operand
/// (difference: increasing in the first, decreasing in the rest), so each event either can
/// only add to the result or only remove from it.
bool pushesIn(CsgOp op, const Event& e) {
  bool subtracted = op == CsgOp::kDifference && e.operand > 0;
  return subtracted ? !e.entering : e.entering;
}

/// The order of tied events from different operands: a union takes its "in" events first
/// (touching solids merge, no inner face), an intersection and a difference their "out"
/// events first (no slivers; a subtracted face flush with the first solid's face removes it).
bool inFirst(CsgOp op) {
  return op == CsgOp::kUnion;
}

/// The crossing reported for a result boundary made by event `made`: that of the
/// lowest-indexed operand among the processed events tied to it (the same surface, same key)
/// pushing the same way, so a face shared by two children always shows the same child. Only
/// tied events count: near an edge the boundary is the surface the ray actually crosses there.
/// Subtracted faces point into the removed solid.
Crossing resultCrossing(CsgOp op, const std::vector<Event>& events, const std::vector<bool>& done,
                        size_t first, size_t last, const Event& made) {
  const Event* best = nullptr;
  bool resultEntering = pushesIn(op, made);
  for (size_t i = first; i < last; ++i)
    if (done[i - first] && events[i].key == made.key &&
        pushesIn(op, events[i]) == resultEntering && (!best || events[i].operand < best->operand))
      best = &events[i];
  Crossing c = *best->crossing;
  if (op == CsgOp::kDifference && best->operand > 0) c.normal = -c.normal;
  return c;
}

}  // namespace

void combineIntervals(CsgOp op, const std::vector<std::vector<Interval>>& operands,
                      const TieTolerance& tolerance, std::vector<Interval>& out) {
  out.clear();
  if (operands.empty()) return;
  std::vector<Event> events;
  for (size_t k = 0; k < operands.size(); ++k)
    for (const Interval& span : operands[k]) {
      events.push_back({span.enter.t, int(k), true, &span.enter});
      events.push_back({span.exit.t, int(k), false, &span.exit});
    }
  // The operand lists arrive sorted, so this is a k-way merge in effect. At equal t an
  // operand's entry goes before its exit, keeping zero-length intervals (tangent rays) intact.
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.t < b.t; });

  std::vector<int> depth(operands.size(), 0);
  std::vector<bool> done;
  bool inside = false;
  Interval current;
  float lastExitKey = std::numeric_limits<float>::quiet_NaN();
  for (size_t first = 0; first < events.size();) {
    // A cluster: every boundary within the tolerance of the previous one. Infinite ends
    // cluster only with equal infinities.
    size_t last = first + 1;
    while (last < events.size()) {
      float a = events[last - 1].t, b = events[last].t;
      if (!(a == b || (std::isfinite(a) && std::isfinite(b) && b - a <= tolerance.at(b)))) break;
      ++last;
    }
    // Ties: a boundary within the tolerance of an earlier one of the same surface (parallel
    // normals) takes its key; every other boundary keeps its own t as key. Rounding only
    // needs forgiving where two operands share a surface: transversal surfaces meeting at an
    // edge keep their computed order, which is right up to float rounding as for a mesh.
    // Issue 18: this sweep used to tie every boundary within the tolerance (1e-5 of the ray's
    // distance scale, ~1e-4 for a camera 7 units away: 100 times float rounding). A ray
    // passing that close to an edge where faces of two operands meet at an angle then lost
    // the thin chord the edge leaves (intersection, difference: exits first), so camera rays
    // went through the solid next to its silhouette, or was reported on the wrong face (the
    // lowest operand's crossing, up to the tolerance before the real boundary: a hit in empty
    // space, or on a face a subtracted solid removes). Found by tests/shapes/csg_oracle_test.
    for (size_t i = first; i < last; ++i) {
      Event& e = events[i];
      e.key = e.t;
      for (size_t j = first; j < i; ++j)
        if (e.t - events[j].t <= tolerance.at(e.t) && sameSurface(*e.crossing, *events[j].crossing)) {
          e.key = events[j].key;
          break;
        }
    }
    // Process the cluster in key order: each operand's own boundaries in their order (a thin
    // chord through one child stays a chord), tied boundaries of different operands in the
    // order the rule prefers.
    done.assign(last - first, false);
    for (size_t n = first; n < last; ++n) {
      size_t pick = last;
      std::vector<bool> blocked(operands.size(), false);  // operand has an earlier pending event
      for (size_t i = first; i < last; ++i) {
        if (done[i - first]) continue;
        const Event& e = events[i];
        if (blocked[size_t(e.operand)]) continue;
        blocked[size_t(e.operand)] = true;
        if (pick == last) {
          pick = i;
          continue;
        }
        const Event& p = events[pick];
        if (e.key != p.key) {
          if (e.key < p.key) pick = i;
          continue;
        }
        bool eFirst = pushesIn(op, e) == inFirst(op), pFirst = pushesIn(op, p) == inFirst(op);
        if (eFirst != pFirst ? eFirst : e.operand < p.operand) pick = i;
      }
      done[pick - first] = true;
      const Event& e = events[pick];
      depth[size_t(e.operand)] += e.entering ? 1 : -1;
      bool nowInside = insideResult(op, depth);
      if (nowInside && !inside) {
        current.enter = resultCrossing(op, events, done, first, last, e);
        if (!out.empty() && (e.key == lastExitKey || current.enter.t <= out.back().exit.t)) {
          current.enter = out.back().enter;  // re-entered within the tie: one interval
          out.pop_back();
        }
      } else if (!nowInside && inside) {
        current.exit = resultCrossing(op, events, done, first, last, e);
        if (current.exit.t < current.enter.t) current.exit.t = current.enter.t;
        out.push_back(current);
        lastExitKey = e.key;
      }
      inside = nowInside;
    }
    first = last;
  }
}

}  // namespace tray

#include "shapes/interval_ops.h"

#include <algorithm>

namespace tray {
namespace {

/// One boundary of one operand: the ray enters or leaves that operand's solid.
struct Event {
  float t;
  int operand;
  bool entering;
  const Crossing* crossing;
};

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

/// The crossing reported for a result boundary made within a tied event: that of the
/// lowest-indexed operand among the processed events pushing the same way, so a face shared by
/// two children always shows the same child. Subtracted faces point into the removed solid.
Crossing resultCrossing(CsgOp op, const std::vector<Event>& events, const std::vector<bool>& done,
                        size_t first, size_t last, bool resultEntering) {
  const Event* best = nullptr;
  for (size_t i = first; i < last; ++i)
    if (done[i - first] && pushesIn(op, events[i]) == resultEntering &&
        (!best || events[i].operand < best->operand))
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
  for (size_t first = 0; first < events.size();) {
    // One tied event: every boundary within the tolerance of the previous one. Infinite
    // ends tie only with equal infinities.
    size_t last = first + 1;
    while (last < events.size()) {
      float a = events[last - 1].t, b = events[last].t;
      if (!(a == b || (std::isfinite(a) && std::isfinite(b) && b - a <= tolerance.at(b)))) break;
      ++last;
    }
    // Process the tie: each operand's own boundaries in their order (a thin chord through one
    // child stays a chord), different operands in the order the rule prefers.
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
        bool eFirst = pushesIn(op, e) == inFirst(op), pFirst = pushesIn(op, p) == inFirst(op);
        if (eFirst != pFirst ? eFirst : e.operand < p.operand) pick = i;
      }
      done[pick - first] = true;
      const Event& e = events[pick];
      depth[size_t(e.operand)] += e.entering ? 1 : -1;
      bool nowInside = insideResult(op, depth);
      if (nowInside && !inside) {
        current.enter = resultCrossing(op, events, done, first, last, true);
        if (!out.empty() && current.enter.t <= out.back().exit.t) {
          current.enter = out.back().enter;  // re-entered within the tie: one interval
          out.pop_back();
        }
      } else if (!nowInside && inside) {
        current.exit = resultCrossing(op, events, done, first, last, false);
        if (current.exit.t < current.enter.t) current.exit.t = current.enter.t;
        out.push_back(current);
      }
      inside = nowInside;
    }
    first = last;
  }
}

}  // namespace tray

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

/// The crossing that makes the result's boundary within events [first, last): the
/// lowest-indexed operand whose own change agrees with the result's change. Every operation
/// is monotone in each operand (difference: increasing in the first, decreasing in the
/// rest), so a change of the result always has such an event.
Crossing resultCrossing(CsgOp op, const std::vector<Event>& events, size_t first, size_t last,
                        bool resultEntering) {
  const Event* best = nullptr;
  for (size_t i = first; i < last; ++i) {
    const Event& e = events[i];
    bool subtracted = op == CsgOp::kDifference && e.operand > 0;
    bool agrees = subtracted ? e.entering != resultEntering : e.entering == resultEntering;
    if (agrees && (!best || e.operand < best->operand)) best = &e;
  }
  if (!best) best = &events[first];  // unreachable for monotone operations; stay defined
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
  // Operand lists arrive sorted, so this is a k-way merge in effect; the tie order (operand,
  // then enters first) only makes the sweep deterministic, the state is decided per event.
  std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
    if (a.t != b.t) return a.t < b.t;
    if (a.operand != b.operand) return a.operand < b.operand;
    return a.entering && !b.entering;
  });

  std::vector<int> depth(operands.size(), 0);
  bool inside = false;
  Interval current;
  for (size_t first = 0; first < events.size();) {
    // Gather one event: every boundary within the tolerance of the previous one. Infinite
    // ends group only with equal infinities.
    size_t last = first + 1;
    while (last < events.size()) {
      float a = events[last - 1].t, b = events[last].t;
      bool same = a == b || (std::isfinite(a) && std::isfinite(b) && b - a <= tolerance.at(b));
      if (!same) break;
      ++last;
    }
    for (size_t i = first; i < last; ++i)
      depth[size_t(events[i].operand)] += events[i].entering ? 1 : -1;
    bool nowInside = insideResult(op, depth);
    if (nowInside && !inside) {
      current.enter = resultCrossing(op, events, first, last, true);
    } else if (!nowInside && inside) {
      current.exit = resultCrossing(op, events, first, last, false);
      out.push_back(current);
    }
    inside = nowInside;
    first = last;
  }
}

}  // namespace tray

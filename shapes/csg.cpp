#include "shapes/csg.h"

#include "core/error.h"

namespace tray {
namespace {

/// Bounds of a child's solid in CSG space, or nothing when the solid is unbounded.
bool childBounds(const CsgChild& c, Bounds3& out) {
  Bounds3 b = c.shape->bounds();
  if (!b.finite()) return false;
  out = c.toCsg.bounds(b);
  return true;
}

Bounds3 overlap(const Bounds3& a, const Bounds3& b) {
  return {max(a.lo, b.lo), min(a.hi, b.hi)};
}

}  // namespace

Csg::Csg(CsgOp op, std::vector<CsgChild> children, std::string name, float tieTolerance)
    : op_(op), children_(std::move(children)), name_(std::move(name)), tieTolerance_(tieTolerance) {
  if (children_.empty()) throw Error("CSG node '" + name_ + "' has no children");
  for (const CsgChild& c : children_)
    if (!c.shape)
      throw Error("CSG node '" + name_ + "' has a child '" + c.name + "' without a shape");
    else if (!c.shape->isSolid())
      throw Error("CSG node '" + name_ + "' has a child '" + c.name +
                  "' that is an open surface, not a solid (cap it: \"capped\": true)");
  computeBounds();
}

void Csg::computeBounds() {
  Bounds3 b;
  switch (op_) {
    case CsgOp::kUnion:
      for (const CsgChild& c : children_) {
        Bounds3 cb;
        if (!childBounds(c, cb)) {
          unboundedReason_ = "union with the unbounded child '" + c.name + "'";
          break;
        }
        b.extend(cb);
      }
      break;
    case CsgOp::kIntersection: {
      bool any = false;
      for (const CsgChild& c : children_) {
        Bounds3 cb;
        if (!childBounds(c, cb)) continue;  // a half-space: the other children limit it
        b = any ? overlap(b, cb) : cb;
        any = true;
      }
      if (!any) unboundedReason_ = "intersection of unbounded children only";
      break;
    }
    case CsgOp::kDifference:
      if (!childBounds(children_[0], b))
        unboundedReason_ = "its first child '" + children_[0].name + "' is unbounded";
      break;
  }
  if (!unboundedReason_.empty()) b = {Vec3(-kInfinity), Vec3(kInfinity)};
  bounds_ = b;
}

void Csg::requireBounded() const {
  if (!bounded()) throw Error("CSG node '" + name_ + "' is unbounded (" + unboundedReason_ + ")");
}

void Csg::intervals(const Ray& ray, std::vector<Interval>& out) const {
  std::vector<std::vector<Interval>> lists(children_.size());
  for (size_t k = 0; k < children_.size(); ++k) {
    const CsgChild& c = children_[k];
    Ray local{c.toCsg.inversePoint(ray.o), c.toCsg.inverseVector(ray.d), -kInfinity, kInfinity};
    c.shape->intervals(local, lists[k]);
    // An empty operand empties an intersection, and an empty first operand a difference.
    bool required = op_ == CsgOp::kIntersection || (op_ == CsgOp::kDifference && k == 0);
    if (required && lists[k].empty()) return;
    for (Interval& span : lists[k])
      for (Crossing* x : {&span.enter, &span.exit}) {
        x->normal = c.toCsg.normal(x->normal);  // inverse transpose: stays perpendicular
        if (x->material < 0) x->material = c.material;
      }
  }
  TieTolerance tol{tieTolerance_, length(ray.o) / length(ray.d)};
  std::vector<Interval> result;
  combineIntervals(op_, lists, tol, result);
  out.insert(out.end(), result.begin(), result.end());
}

bool Csg::intersect(const Ray& ray, Hit& hit) const {
  std::vector<Interval> spans;
  intervals(ray, spans);
  for (const Interval& s : spans)
    for (const Crossing* c : {&s.enter, &s.exit}) {
      if (c->t >= ray.tmax) return false;
      if (c->t > ray.tmin) {
        hit.t = c->t;
        hit.normal = c->normal;
        hit.uv = c->uv;
        hit.material = c->material;
        return true;
      }
    }
  return false;
}

CsgOp csgOpFromName(const std::string& name) {
  if (name == "union") return CsgOp::kUnion;
  if (name == "intersection") return CsgOp::kIntersection;
  if (name == "difference") return CsgOp::kDifference;
  throw Error("unknown CSG op '" + name + "' (known: union, intersection, difference)");
}

const char* csgOpName(CsgOp op) {
  switch (op) {
    case CsgOp::kUnion:
      return "union";
    case CsgOp::kIntersection:
      return "intersection";
    case CsgOp::kDifference:
      return "difference";
  }
  return "?";
}

}  // namespace tray

#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/transform.h"
#include "shapes/interval_ops.h"
#include "core/shape.h"

namespace tray {

/// One operand of a CSG node: a solid placed in the CSG node's object space.
struct CsgChild {
  std::shared_ptr<const Shape>
      shape;          ///< sphere, box, plane (the half-space y <= 0), MeshSolid, Csg
  Transform toCsg;    ///< child object space -> CSG object space
  int material = -1;  ///< material of this child's surfaces; -1: the CSG's own
  std::string name;   ///< for messages (the glTF node's name)
};

/// Constructive solid geometry: the union, intersection or difference (first minus the rest)
/// of child solids, as one shape. Every query computes each child's intervals along the whole
/// line in the child's space (t is shared: the ray's direction is transformed, not
/// normalised), combines them (shapes/interval_ops.h) and reads off the boundaries. Roth,
/// "Ray Casting for Modeling Solids", Computer Graphics and Image Processing 18 (1982).
///
/// A result boundary reports the outward normal of the result (flipped on the faces of
/// subtracted solids) and the material of the child whose surface it is (Hit::material).
class Csg final : public Shape {
 public:
  /// Relative tolerance under which two boundaries count as one (see TieTolerance).
  static constexpr float kDefaultTieTolerance = 1e-5f;

  /// Throws tray::Error when there are no children or a child has no shape.
  Csg(CsgOp op, std::vector<CsgChild> children, std::string name = "csg",
      float tieTolerance = kDefaultTieTolerance);

  /// Bounds of the solid: intersection of the children's bounds, the first child's for a
  /// difference, their union for a union. A half-space child counts as the whole space, so
  /// the result stays finite when the solid is finite (e.g. a sphere cut by a half-space), and
  /// is infinite when it is not (a union with a half-space).
  Bounds3 bounds() const override { return bounds_; }
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray& ray, std::vector<Interval>& out) const override;

  /// False when the solid reaches infinity (a union with a half-space, a half-space minus
  /// something): such a node cannot be placed in a scene on its own, only used as a child.
  bool bounded() const { return unboundedReason_.empty(); }
  /// Throws tray::Error "CSG node 'name' is unbounded (...)" unless bounded().
  void requireBounded() const;

  CsgOp op() const { return op_; }
  const std::vector<CsgChild>& children() const { return children_; }
  const std::string& name() const { return name_; }

 private:
  void computeBounds();

  CsgOp op_;
  std::vector<CsgChild> children_;
  std::string name_;
  float tieTolerance_;
  Bounds3 bounds_;
  std::string unboundedReason_;  ///< empty when bounded
};

/// "union", "intersection", "difference"; throws tray::Error naming the choices otherwise.
CsgOp csgOpFromName(const std::string& name);
const char* csgOpName(CsgOp op);

}  // namespace tray

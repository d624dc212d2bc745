#pragma once
#include <memory>
#include <string>

#include "core/accelerator.h"
#include "core/scene.h"
#include "core/shape.h"

namespace tray {

/// A closed triangle mesh seen as a solid, so it can be a CSG child. It owns a private Scene
/// holding only this mesh and an accelerator over it; intervals come from the accelerator's
/// all-hits query along the whole line, each hit classified as entering (the ray runs against
/// the triangle's outward normal) or leaving, and paired by winding number.
class MeshSolid final : public Shape {
 public:
  /// Checks that the mesh is closed and consistently wound (every edge, welded by exact
  /// position, is used once in each direction) and turns an inward-wound mesh outward.
  /// Throws tray::Error naming the mesh otherwise. `accelerator` builds the all-hits query
  /// over the private scene (accel/registry.h: acceleratorFactory("embree")).
  MeshSolid(TriangleMesh mesh, const AcceleratorFactory& accelerator);
  MeshSolid(const MeshSolid&) = delete;  // the accelerator refers to scene_
  MeshSolid& operator=(const MeshSolid&) = delete;

  Bounds3 bounds() const override { return bounds_; }
  bool intersect(const Ray& ray, Hit& hit) const override;
  void intervals(const Ray& ray, std::vector<Interval>& out) const override;
  const TriangleMesh& mesh() const { return scene_.meshes[0]; }

 private:
  /// Unnormalised outward normal of triangle i (object space).
  Vec3 triangleNormal(uint32_t i) const;
  Vec2 uvAt(const Hit& hit) const;

  Scene scene_;
  std::unique_ptr<Accelerator> accel_;
  Bounds3 bounds_;
};

}  // namespace tray

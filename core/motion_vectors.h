#pragma once
// Screen-space motion vectors for compositing (docs/aovs.md, "Motion vectors"): how far, in
// pixels, the surface point a camera sample hit moved over the last frame, as Nuke's
// VectorBlur reads them.
#include "core/camera_matrices.h"
#include "core/integrator.h"
#include "core/scene.h"

namespace tray {

class MotionVectors {
 public:
  /// `camera` as it renders this frame (its previousToWorld, when set, one frame before);
  /// the primitives' frame and previous-frame placements come from `scene`.
  MotionVectors(const Scene& scene, const CameraDesc& camera, int width, int height);
  /// (u, v) for the first hit `hit`: the point's raster position in this frame minus its
  /// position in the previous frame (time - 1/fps), each through that frame's camera; u to the
  /// right, v up (Nuke's y axis). Zero where nothing was hit or the point is behind a camera.
  Vec2 at(const PrimaryHit& hit) const;

 private:
  /// Raster position (x right, y down, pixels) of world point p through `worldToNdc`; false
  /// behind the camera.
  bool project(const ExrMatrix& worldToNdc, const Vec3& p, Vec2& raster) const;

  const Scene& scene_;
  ExrMatrix now_, before_;
  int width_, height_;
};

}  // namespace tray

#pragma once
// Every crossing of an analytic shape's boundary inside a ray's range: what an all-hits query
// (CSG on ray intervals, docs/csg.md) is told of a shape, by both accelerators alike
// (accel/bvh_accelerator.cpp and Embree's user geometry, accel/embree_shape_geometry.cpp).
#include <cmath>
#include <vector>

#include "core/hit.h"
#include "core/motion.h"
#include "core/ray.h"
#include "core/scene.h"
#include "core/shape.h"

namespace tray {

/// Calls report(Hit&) for each entry and exit of primitive p's shape with tmin < t < tmax (its
/// t, normal, uv and material set; the caller adds what identifies the primitive).
template <class Report>
void forEachShapeCrossing(const Primitive& p, const Ray& ray, Report&& report) {
  Transform moved;
  const Transform* toWorld = placementAt(p, ray.time, moved);
  if (!toWorld) return;
  Ray local{toWorld->inversePoint(ray.o), toWorld->inverseVector(ray.d), ray.tmin, ray.tmax};
  std::vector<Interval> spans;
  p.shape->intervals(local, spans);
  for (const Interval& s : spans)
    for (const Crossing& c : {s.enter, s.exit})
      if (c.t > ray.tmin && c.t < ray.tmax && std::isfinite(c.t)) {
        Hit h;
        h.t = c.t;
        h.normal = c.normal;
        h.uv = c.uv;
        h.material = c.material;
        report(h);
      }
}

}  // namespace tray

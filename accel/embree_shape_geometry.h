#pragma once
// Analytic shapes in Embree (accel/embree_accelerator.cpp): a shape primitive that Embree does
// not intersect natively (accel/embree_native.h) is a user geometry of one primitive whose
// callbacks trace Scene::intersectShape. Its hits carry the shape's normal as Ng, its uv as
// u, v and its material + 1 as primID (accel/embree_rays.h, hitFromEmbree). All-hits queries
// (a context filter set) get every crossing of the shape's boundary within the ray's range;
// Embree does not call filters for user geometry itself (RenderKit/embree#478), so the
// callback does.
#include <embree3/rtcore.h>

#include <cstdint>

#include "core/scene.h"

namespace tray {

/// What one shape's callbacks read.
struct ShapeUserData {
  const Scene* scene;
  uint32_t primitive;
};

/// The user geometry of shape primitive data.primitive (over its motion steps when it moves),
/// not committed; `data` must outlive it.
RTCGeometry embreeShapeGeometry(RTCDevice device, ShapeUserData& data);

}  // namespace tray

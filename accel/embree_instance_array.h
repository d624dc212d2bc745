#pragma once
// Instance arrays in Embree 3 (core/instance_array.h): Embree 3.13 has no instance-array
// geometry (RTC_GEOMETRY_TYPE_INSTANCE_ARRAY came with Embree 4), and an
// RTC_GEOMETRY_TYPE_INSTANCE per instance costs about 400 bytes
// (docs/bench/instancing-2026-12-06.md). One user geometry stands for the whole array instead:
// its primitive k is instance k, bounded by the mesh's box placed by the instance; its
// callbacks move the ray into the instance's object space and trace the mesh's own scene, as
// Embree's user_geometry tutorial instances objects in Embree 3 (context->instID set around the
// inner query, so that the hit reports the array's geometry id as its instance).
#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "accel/bvh_instance_boxes.h"
#include "core/scene.h"

namespace tray {

/// Instances per user primitive: the primitive's box is its group's, and its callbacks test
/// the group's instances' own boxes (accel/bvh_instance_boxes.h, as the in-house BVH's leaves)
/// before moving the ray into any of them. An eighth of the primitives lets Embree build its
/// medium (SAH) quality top tree within the memory budget.
constexpr uint32_t kEmbreeArrayGroup = 8;
constexpr int kEmbreeArrayBoxNodes = int(kEmbreeArrayGroup / 4);

/// What the callbacks of one array's user geometry read.
struct EmbreeArrayData {
  const InstanceArray* array = nullptr;
  RTCScene meshScene = nullptr;  ///< the mesh's own scene (geometry id 0)
  Bounds3 meshBounds;            ///< in object space
  /// Group g's instance boxes (world space): kEmbreeArrayBoxNodes from g * kEmbreeArrayBoxNodes.
  std::vector<InstanceBoxes4> boxes;
};

/// Fills data.boxes and makes the user geometry of `data` (which must outlive it), not
/// committed: primitive g is instances g * kEmbreeArrayGroup onwards.
RTCGeometry embreeInstanceArray(RTCDevice device, EmbreeArrayData& data);

/// A hit inside an array reports the instance in RTCHit::geomID (the mesh scene's own geometry
/// id is always 0, so it carries nothing there); hitFromEmbree reads it as Hit::instance. Inner
/// filters (all-hits queries) see the mesh's geometry id 0: they read the instance here, set
/// by the callback around its inner query on this thread.
uint32_t embreeArrayInstanceInFlight();

}  // namespace tray

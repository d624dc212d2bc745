#pragma once
// Batched Embree queries for Accelerator::intersectBatch / occludedBatch: the stream API
// (rtcIntersect1M) or 8-wide packets (rtcIntersect8), chosen by EmbreeBatch. Triangle
// geometry only (instances of meshes): user geometry's callbacks read one ray.
#include <embree3/rtcore.h>

#include <span>

#include "accel/embree_accelerator.h"
#include "core/hit.h"
#include "core/ray.h"
#include "core/scene.h"

namespace tray {

/// found[i]: rays[i] hit something in top, hits[i] its closest hit (as rtcIntersect1 would).
/// `coherent`: the rays are (camera rays in pixel order), and Embree's packets are told so.
void embreeIntersectBatch(RTCScene top, const Scene& scene, EmbreeBatch mode,
                          std::span<const Ray> rays, std::span<Hit> hits, std::span<uint8_t> found,
                          bool coherent = false);
/// blocked[i]: something lies on rays[i].
void embreeOccludedBatch(RTCScene top, const Scene& scene, EmbreeBatch mode,
                         std::span<const Ray> rays, std::span<uint8_t> blocked);

}  // namespace tray

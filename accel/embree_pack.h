#pragma once
// Eight rays into an Embree 8-ray packet in SIMD (accel/embree_pack.cpp).
#include <embree3/rtcore.h>

#include <cstdint>

#include "core/ray.h"

namespace tray {

/// Rays rays[0..7] into the lanes of `packet`, as toLane (accel/embree_batch.cpp) fills them:
/// origin, tnear, direction, time, tfar, mask all ones, id firstId + lane, flags 0. Returns
/// whether Embree accepts all eight (embreeAccepts, accel/embree_rays.h).
bool packRays8(const Ray* rays, uint32_t firstId, RTCRay8& packet);

}  // namespace tray

#pragma once
// One guard for what TRay hands to Embree (issue 40): Embree asserts, and aborts the process,
// on a ray whose origin or direction has a coordinate beyond about 1.8e18 (RayK::valid,
// FLT_LARGE). Meshes are refused beyond 1e18 when read (gltf/gltf_meshes.cpp); the values rays
// are made from besides (the camera's place and lens, a punctual light's position) are checked
// here, once the scene is posed at the render's time, against the same bound as the
// accelerator's extent (1e17: a shadow ray's unnormalised direction, the difference of two such
// points, stays within Embree's range).
#include <string>

#include "core/camera.h"
#include "core/scene.h"

namespace tray {

/// The largest coordinate or length a ray is made from.
inline constexpr float kMaxRayCoordinate = 1e17f;

/// Throws tray::Error ("SCENE: the camera 'NAME' ... beyond 1e17 ...", one line) when the
/// camera (its position at every motion step, lens radius, focus distance, orthographic
/// extents, near distance) or a punctual light's position is NaN, infinite or beyond
/// kMaxRayCoordinate.
void checkRayRange(const std::string& sceneName, const Scene& scene, const CameraDesc& camera);

}  // namespace tray

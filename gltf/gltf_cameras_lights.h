#pragma once
// glTF cameras (glTF 2.0 §3.10) and KHR_lights_punctual lights, before placement by nodes.
#include "core/camera.h"
#include "core/light.h"
#include "gltf/gltf_context.h"

namespace tray {

/// Camera `index` with its projection checked (finite, positive yfov below pi and znear,
/// non-zero magnifications, zfar beyond znear); toWorld is left for the node to set.
CameraDesc convertCamera(const GltfContext& ctx, int index);

/// Light `index` of KHR_lights_punctual. intensity = color x intensity with no photometric
/// conversion (docs/scene-format.md, "Light units"); position and direction are set by the
/// node. `range` is ignored.
PunctualLightDesc convertLight(const GltfContext& ctx, int index);

}  // namespace tray

#pragma once
// One warning line per glTF feature a file uses that TRay does not render, so that nothing is
// dropped silently (unknown extensions are warned by gltf_validate).
#include "gltf/gltf_context.h"

namespace tray {

/// Warns about ignored attributes (TEXCOORD_2+, COLOR_1+, JOINTS_2+ / WEIGHTS_2+), texture
/// references to uv sets above 1 and occlusion textures: one line each, with a count.
void warnUnsupported(const GltfContext& ctx);

}  // namespace tray

#pragma once
// One warning line per glTF feature a file uses that TRay does not render, so that nothing is
// dropped silently (unknown extensions are warned by gltf_validate).
#include "io/gltf_context.h"

namespace tray {

/// Warns about animations, skins, morph targets, ignored attributes (TEXCOORD_2+, COLOR_1+,
/// JOINTS/WEIGHTS), texture references to uv sets above 1 and occlusion textures: one line
/// each, with a count.
void warnUnsupported(const GltfContext& ctx);

}  // namespace tray

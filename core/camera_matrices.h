#pragma once
// The camera as OpenEXR's standard attributes describe it, for compositors (Nuke's exr/
// metadata, camera-from-metadata tools). ImfStandardAttributes.h defines both matrices.
#include <array>

#include "core/camera.h"

namespace tray {

/// A 4x4 matrix as Imath::M44f stores it: row-major, for row vectors (p' = p M), so the
/// translation is in the last row.
using ExrMatrix = std::array<float, 16>;

/// worldToCamera: world to RenderMan's camera space (left-handed: +x right, +y up, +z the
/// viewing direction), i.e. the glTF camera space with z negated.
ExrMatrix exrWorldToCamera(const CameraDesc& camera);

/// worldToNDC: world to normalised device coordinates, (0, 0) the top-left and (1, 1) the
/// bottom-right corner of the full image (width x height, the display window): multiply, divide
/// by w, discard z (which is 1 / view depth for perspective cameras, the depth for orthographic).
ExrMatrix exrWorldToNdc(const CameraDesc& camera, int width, int height);

}  // namespace tray

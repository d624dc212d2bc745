#pragma once
// The declared options in the EXR metadata: one attribute per option that decides a render's
// pixels, so that a file says how it was made.
#include "core/render_options.h"
#include "io/image_output.h"

namespace tray {

/// Appends to `out` one "tray:<option>" attribute (the name in camelCase: tray:pixelSampler,
/// tray:maxDepth) per option that decides the pixels of this render: render-wide ones, the
/// integrator's and the wrapped integrator's. Strings, except tray:spp, a float as readers
/// before this table expect.
void addOptionMetadata(const RenderSettings& settings, ImageOutputOptions& out);

}  // namespace tray

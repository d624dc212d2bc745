#pragma once
#include "core/integrator.h"

namespace tray {

/// Unidirectional path tracing with next-event estimation and multiple importance sampling
/// (Veach 1997, ch. 9; the structure of Mitsuba 3's `path` and pbrt-v4's PathIntegrator).
/// Depth counts path segments from the camera as Mitsuba does: max depth 1 shows only
/// directly visible emitters, 2 adds direct lighting; default 8. See docs/path-tracing.md.
std::unique_ptr<Integrator> makePath(const RenderContext& ctx);
/// Its options: --max-depth (default 8), --rr-depth (5), --rr-survival, --clamp-indirect,
/// --debug-nan.
const std::vector<OptionSpec>& pathOptions();

}  // namespace tray

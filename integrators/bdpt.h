#pragma once
#include "core/integrator.h"

namespace tray {

/// Bidirectional path tracing with multiple importance sampling over all strategies (Veach
/// 1997 ch. 10; pbrt-v3 16.3's structure): a frame-level integrator whose pixel pass takes the
/// strategies with two or more camera vertices and whose light-tracing pass (t = 1) splats
/// onto the pixels, reduced in a fixed order. Depth as path's (segments from the camera).
/// See docs/bdpt.md.
std::unique_ptr<Integrator> makeBdpt(const RenderContext& ctx);
/// Its options: --max-depth, --light-sampler, --triangle-sampling (as path's) and
/// --bdpt-strategy (all, or one family unweighted: a debugging check).
const std::vector<OptionSpec>& bdptOptions();

}  // namespace tray

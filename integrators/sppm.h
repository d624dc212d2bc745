#pragma once
#include "core/integrator.h"

namespace tray {

/// Stochastic progressive photon mapping (Hachisuka & Jensen 2009; docs/sppm.md): each of --spp
/// iterations traces one camera path per pixel to its first non-delta vertex (a visible point,
/// with direct light by next-event estimation), then --photons photons from the lights, whose
/// hits after their first bounce are gathered at the visible points within each pixel's radius;
/// the radii shrink by --sppm-alpha. Consistent, not unbiased. A frame-level integrator
/// (docs/frame-integrators.md).
std::unique_ptr<Integrator> makeSppm(const RenderContext& ctx);
/// Its options: --max-depth (path's meaning), --photons, --sppm-radius, --sppm-alpha.
const std::vector<OptionSpec>& sppmOptions();

}  // namespace tray

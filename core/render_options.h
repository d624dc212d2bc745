#pragma once
// The render-wide options, which every integrator reads through the Integrator base class, and
// RenderSettings, the option values of one render (docs/options.md).
#include <vector>

#include "core/options.h"

namespace tray {

/// --integrator, --spp, --seed, --sampler, --pixel-sampler, --filter (the last three declared in
/// core/sampler.cpp, core/pixel_sampler.cpp and core/filter.cpp), --env, --env-rotate,
/// --env-intensity (applied by io/environment_map.h), --time, --fps, --animation
/// (core/animation_time.cpp). --integrator has no choices
/// here: core does not know the registry (integrators/registry.h checks the name).
const std::vector<OptionSpec>& renderOptions();

/// The option values of one render. The render-wide options are declared from the start;
/// makeIntegrator (integrators/registry.h) declares the chosen integrator's own options (and
/// those of the integrator it wraps) before creating it. Tests set values by name:
/// `settings.set("spp", 16)`.
class RenderSettings : public OptionValues {
 public:
  RenderSettings() { declare(renderOptions()); }
};

/// Whether the render runs in passes (--noise-threshold or --time-limit set;
/// render/pass_renderer.h): a pixel may then stop after any number of its samples.
bool rendersInPasses(const RenderSettings& settings);

}  // namespace tray

#pragma once
// The declared options (docs/options.md) on the command line: what tray-render does with the
// render-wide specs and those of every registered integrator (their EXR metadata:
// render/option_metadata.h).
#include <CLI/CLI.hpp>

#include "core/render_options.h"

namespace tray {

/// Adds one CLI11 option per declared name: the render-wide options and those of every
/// registered integrator (an option several integrators declare, like --max-depth, is one
/// command-line option whose help names each one's default). A given value is parsed as the
/// spec's type (tray::Error naming the option otherwise) and set in `settings`, which must
/// outlive the app; ranges and choices are checked by validateOptions after parsing.
void addRenderOptions(CLI::App& app, RenderSettings& settings);

}  // namespace tray

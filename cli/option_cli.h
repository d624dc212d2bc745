#pragma once
// The declared options (docs/options-design.md) on the command line: what tray-render does with
// the render-wide specs and those of every registered integrator (their EXR metadata:
// render/option_metadata.h).
#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/render_options.h"

namespace tray {

/// The --help groups of the declared options: render-wide ones, and integrators' own.
inline constexpr const char* kRenderGroup = "Render options";
inline constexpr const char* kIntegratorGroup = "Integrator options";

/// The declared options as the command line offers them: the render-wide specs, then each
/// registered integrator's, in registry order, with the integrator names filled in as the
/// choices of --integrator and of a wrapper's inner option. addRenderOptions and the option
/// reference (cli/options_doc.h) both read this.
struct DeclaredOptions {
  std::vector<OptionSpec> renderWide;
  std::vector<std::pair<std::string, std::vector<OptionSpec>>> integrators;  ///< (name, specs)
};
DeclaredOptions declaredOptions();

/// Adds one CLI11 option per declared name: the render-wide options and those of every
/// registered integrator (an option several integrators declare, like --max-depth, is one
/// command-line option whose help names each one's default). A given value is parsed as the
/// spec's type (tray::Error naming the option otherwise) and set in `settings`, which must
/// outlive the app; ranges and choices are checked by validateOptions after parsing.
void addRenderOptions(CLI::App& app, RenderSettings& settings);

/// An option given an empty value (`--env ''`) is a mistake, not its default (omit the option
/// for that): every option that takes a value carries this check, the declared ones from
/// addRenderOptions, the command line's own from cli/cli_options.cpp.
CLI::Validator nonEmptyValue();

}  // namespace tray

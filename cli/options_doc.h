#pragma once
// tray-render's option reference in Markdown (docs/options.md, written by
// tools/gen-options-doc.sh): made from the same CLI11 app and option declarations as --help, so
// the reference cannot list an option the command line lacks, or miss one it has.
#include <CLI/CLI.hpp>
#include <string>

namespace tray {

/// Every visible option of `app`, one table per --help group in --help's order. Options made
/// from declarations (cli/option_cli.h) show their type, default, range or choices from the
/// spec, integrator options one table per integrator; the others what CLI11 knows of them.
std::string optionsMarkdown(const CLI::App& app);

/// Adds --help-markdown to `app` (in `group`): prints optionsMarkdown(app) and exits 0, before
/// the required arguments are checked, as --help does.
void addHelpMarkdownFlag(CLI::App& app, const std::string& group);

}  // namespace tray

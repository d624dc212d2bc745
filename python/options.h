#pragma once
// tray-render's command line read for Python: tray.render's keywords become an argument list
// (python/tray/__init__.py) that the command line's own parser and checks read.
#include <string>
#include <vector>

#include "cli/cli_options.h"

namespace tray::python {

/// The options `args` give (a command line without the program name: the scene, then
/// --name=value each), parsed and checked as tray-render does them; throws tray::Error with
/// the message tray-render prints after "tray-render: error: ". Without --output nothing is
/// written (tray-render's default out.exr is the command line's).
CliOptions parseOptions(const std::vector<std::string>& args);

/// The long names of every option tray-render takes (without "--"), as Python keywords
/// spell them: '_' for '-'.
std::vector<std::string> optionNames();

}  // namespace tray::python

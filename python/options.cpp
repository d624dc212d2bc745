#include "python/options.h"

#include <CLI/CLI.hpp>

#include "cli/cli_job.h"
#include "core/error.h"

namespace tray::python {

CliOptions parseOptions(const std::vector<std::string>& args) {
  CliOptions o;
  CLI::App app{"tray"};
  addCliOptions(app, o);
  std::vector<const char*> argv{"tray"};
  for (const std::string& a : args) argv.push_back(a.c_str());
  try {
    app.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    throw Error(e.what());
  }
  if (app.count("--output") == 0) o.outputs.clear();
  checkCliOptions(o);
  return o;
}

/// The long names of every option tray-render takes (without "--"), as Python keywords
/// spell them: '_' for '-'.
std::vector<std::string> optionNames() {
  CliOptions o;
  CLI::App app{"tray"};
  addCliOptions(app, o);
  std::vector<std::string> names;
  for (const CLI::Option* opt : app.get_options())
    for (std::string name : opt->get_lnames()) {
      for (char& c : name)
        if (c == '-') c = '_';
      names.push_back(name);
    }
  return names;
}

}  // namespace tray::python

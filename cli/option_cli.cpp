#include "cli/option_cli.h"

#include <cctype>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "integrators/registry.h"

namespace tray {
namespace {

/// One command-line option: the first spec of its name, and the help of every declaration.
/// Integrators declaring it alike (path and path-wavefront share their options) share one
/// entry: "path, path-wavefront: ...".
struct CliOption {
  OptionSpec spec;
  std::vector<OptionSpec> declarations;  ///< every integrator's (or the render-wide) spec
  std::vector<std::pair<std::string, std::string>> parts;  ///< (owners, description)
  std::string help() const {
    std::string h;
    for (const auto& [owners, text] : parts)
      h += (h.empty() ? "" : "; ") + (owners.empty() ? "" : owners + ": ") + text;
    return h;
  }
};

std::vector<CliOption> cliOptions() {
  std::vector<CliOption> out;
  auto add = [&](const OptionSpec& spec, const std::string& owner) {
    const std::string text = describeOption(spec);
    for (CliOption& o : out)
      if (o.spec.name == spec.name) {
        o.declarations.push_back(spec);
        for (auto& [owners, described] : o.parts)
          if (described == text && !owners.empty()) {
            owners += ", " + owner;
            return;
          }
        o.parts.emplace_back(owner, text);
        return;
      }
    out.push_back({spec, {spec}, {{owner, text}}});
  };
  const DeclaredOptions declared = declaredOptions();
  for (const OptionSpec& spec : declared.renderWide) add(spec, "");
  for (const auto& [name, specs] : declared.integrators)
    for (const OptionSpec& spec : specs) add(spec, name);
  return out;
}

const char* typeName(const OptionSpec& spec) {
  switch (spec.type) {
    case OptionType::kInt:
      return "INT";
    case OptionType::kFloat:
      return "FLOAT";
    case OptionType::kBool:
      return "";
    case OptionType::kString:
      return spec.choices.empty() ? "TEXT" : "NAME";
  }
  return "";
}

/// CLI11 2.1 sums a flag's values with std::stoll, so `--debug-nan=xyz` threw
/// std::invalid_argument past its own ParseError (found by fuzz/options_fuzz). This check runs
/// CLI11's own conversion first and turns its exception into the usual one-line usage error.
CLI::Validator flagValueCheck() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          CLI::detail::to_flag_value(text);
          return {};
        } catch (const std::exception&) {
          return "expected true/false, on/off, yes/no or a number, got '" + text + "'";
        }
      },
      "", "flag value");
}

}  // namespace

CLI::Validator nonEmptyValue() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        return text.empty() ? "an empty value (omit the option for its default)" : std::string();
      },
      "", "non-empty");
}

DeclaredOptions declaredOptions() {
  // Integrator names are known here, not in core or in a wrapper's own file: the help lists
  // them (the registry checks them).
  std::vector<std::string> names;
  for (const auto& e : integratorRegistry()) names.push_back(e.name);
  DeclaredOptions out;
  for (OptionSpec spec : renderOptions()) {
    if (spec.name == "integrator") spec.choices = names;
    out.renderWide.push_back(std::move(spec));
  }
  for (const auto& e : integratorRegistry()) {
    std::vector<OptionSpec> specs = e.options;
    for (OptionSpec& spec : specs)
      if (spec.name == e.innerOption) spec.choices = names;
    out.integrators.emplace_back(e.name, std::move(specs));
  }
  return out;
}

void addRenderOptions(CLI::App& app, RenderSettings& settings) {
  for (const CliOption& o : cliOptions()) {
    const OptionSpec spec = o.spec;
    const std::string flag = "--" + spec.name;
    const std::string group = o.parts.front().first.empty() ? kRenderGroup : kIntegratorGroup;
    if (spec.type == OptionType::kBool) {
      app.add_flag_function(
             flag, [&settings, spec](int64_t count) { settings.set(spec.name, count > 0); },
             o.help())
          ->check(flagValueCheck())
          ->group(group);
      continue;
    }
    // Checked as it is read, against its declarations (valid for one of them), whichever
    // integrator runs: an option of another integrator is not ignored unchecked (issue 40:
    // `--inner nan` with whitted was taken).
    app.add_option_function<std::string>(
           flag,
           [&settings, spec, declarations = o.declarations](const std::string& text) {
             const OptionValue value = parseOptionValue(spec, text);
             for (size_t d = 0; d < declarations.size(); ++d) {
               try {
                 validateOptionValue(declarations[d], value);
                 break;
               } catch (const Error&) {
                 if (d + 1 == declarations.size()) throw;
               }
             }
             settings.setValue(spec.name, value);
           },
           o.help())
        ->type_name(typeName(spec))
        ->check(nonEmptyValue())
        ->group(group);
  }
}

}  // namespace tray

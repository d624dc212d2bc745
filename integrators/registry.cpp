#include "integrators/registry.h"

#include <algorithm>

#include "core/error.h"
#include "integrators/adaptive.h"
#include "integrators/bdpt.h"
#include "integrators/path.h"
#include "integrators/path_wavefront.h"
#include "integrators/sppm.h"
#include "integrators/whitted.h"

namespace tray {
namespace {

// The integrator table: a new integrator is one file plus one line here (its options travel
// with it, declared beside its code; docs/options-design.md).
std::vector<IntegratorEntry>& table() {
  static std::vector<IntegratorEntry> entries = {
      {"whitted", "recursive ray tracing: Phong, shadows, mirror reflection, refraction",
       makeWhitted, whittedOptions(), ""},
      {"adaptive", "adaptive supersampling around --inner: corners, subdivide where they differ",
       makeAdaptive, adaptiveOptions(), "inner"},
      // `path` runs the wavefront driver (issue 16: the same pixels, faster on every bench
      // scene, docs/wavefront.md); `path-scalar` traces one path at a time, the reference.
      {"path",
       "path tracing: MIS next-event estimation, GGX/dielectric BSDFs, area lights; each "
       "bounce of a tile's samples traced as one batch",
       makePathWavefront, pathOptions(), "", true},
      {"path-scalar", "path's estimator one path at a time (the reference: the same pixels)",
       makePath, pathOptions(), "", true},
      {"path-wavefront", "another name for path (its wavefront driver)", makePathWavefront,
       pathOptions(), "", true},
      {"bdpt",
       "bidirectional path tracing: camera and light subpaths, every connection MIS-weighted; "
       "light tracing splats (caustics from point and spot lights)",
       makeBdpt, bdptOptions(), "", true},
      {"sppm",
       "stochastic progressive photon mapping: caustics and light through glass; consistent, "
       "iterations = --spp, --photons per iteration (docs/sppm.md)",
       makeSppm, sppmOptions(), ""},
  };
  return entries;
}

}  // namespace

const std::vector<IntegratorEntry>& integratorRegistry() {
  return table();
}

void registerIntegrator(IntegratorEntry entry) {
  for (const auto& e : table())
    if (e.name == entry.name) throw Error("integrator '" + entry.name + "' is registered twice");
  table().push_back(std::move(entry));
}

const IntegratorEntry& findIntegrator(const std::string& name) {
  for (const auto& e : integratorRegistry())
    if (name == e.name) return e;
  std::string known;
  for (const auto& e : integratorRegistry()) known += (known.empty() ? "" : ", ") + e.name;
  throw Error("unknown integrator '" + name + "' (known: " + known + ")");
}

namespace {

/// The integrators that render, outermost first ("adaptive", "whitted"), read from `bound`
/// (withIntegratorOptions: the inner options' defaults declared); at most 8 deep.
std::vector<const IntegratorEntry*> chainOf(const RenderSettings& bound) {
  std::vector<const IntegratorEntry*> chain{&findIntegrator(bound.getString("integrator"))};
  while (chain.size() < 8 && !chain.back()->innerOption.empty())
    chain.push_back(&findIntegrator(bound.getString(chain.back()->innerOption)));
  return chain;
}

}  // namespace

bool unlitSurfacesLight(const RenderSettings& settings) {
  const IntegratorEntry& innermost = *chainOf(withIntegratorOptions(settings)).back();
  // A wrapper's inner integrator decides (none: a chain deeper than 8).
  return innermost.innerOption.empty() && innermost.unlitSurfacesLight;
}

RenderSettings withIntegratorOptions(const RenderSettings& settings, const std::string& name) {
  // From the values alone: options a caller declared for another integrator do not leak in.
  RenderSettings bound;
  for (const auto& [option, value] : settings.given()) bound.setValue(option, value);
  std::vector<std::string> seen;
  std::string wanted = name.empty() ? bound.getString("integrator") : name;
  for (;;) {
    const IntegratorEntry& e = findIntegrator(wanted);
    bound.declare(e.options);
    seen.push_back(e.name);
    if (e.innerOption.empty()) break;
    wanted = bound.getString(e.innerOption);
    // A wrapper around itself: its factory refuses it with a message of its own.
    if (std::find(seen.begin(), seen.end(), wanted) != seen.end()) break;
  }
  return bound;
}

void validateOptions(const RenderSettings& settings) {
  withIntegratorOptions(settings).validate();
  // Options of integrators not chosen are checked too: a bad value is a mistake either way.
  for (const auto& given : settings.given()) {
    // Named, not structured bindings: clang 14 (the fuzz build) cannot capture those.
    const auto& name = given.first;
    const auto& value = given.second;
    bool known = false;
    auto check = [&](const std::vector<OptionSpec>& specs) {
      for (const OptionSpec& spec : specs)
        if (spec.name == name) validateOptionValue(spec, value), known = true;
    };
    check(renderOptions());
    for (const auto& e : integratorRegistry()) check(e.options);
    if (!known) throw Error("unknown option --" + name);
  }
}

std::vector<std::string> unusedOptionWarnings(const RenderSettings& settings) {
  const RenderSettings bound = withIntegratorOptions(settings);
  // The integrators that render, as the command line names them: "whitted", or
  // "adaptive --inner path".
  const std::vector<const IntegratorEntry*> chain = chainOf(bound);
  std::string chosen = chain.front()->name;
  for (size_t i = 1; i < chain.size(); ++i)
    chosen += " --" + chain[i - 1]->innerOption + " " + chain[i]->name;
  std::vector<std::string> warnings;
  for (const auto& given : settings.given()) {
    const std::string& name = given.first;
    if (bound.find(name)) continue;  // render-wide or read by the chosen integrators
    std::string takers;
    for (const auto& e : integratorRegistry())
      if (std::any_of(e.options.begin(), e.options.end(),
                      [&](const OptionSpec& s) { return s.name == name; }))
        takers += (takers.empty() ? "" : ", ") + e.name;
    if (takers.empty()) continue;  // not an integrator's option (validateOptions says so)
    warnings.push_back("--" + name + " has no effect with --integrator " + chosen +
                       " (an option of " + takers + ")");
  }
  return warnings;
}

std::unique_ptr<Integrator> makeIntegrator(const RenderContext& ctx, const std::string& name) {
  const IntegratorEntry& e =
      findIntegrator(name.empty() ? ctx.settings.getString("integrator") : name);
  RenderContext bound = ctx;
  bound.settings = withIntegratorOptions(ctx.settings, e.name);
  bound.settings.validate();
  return e.create(bound);
}

}  // namespace tray

#pragma once
// The integrator plugins by name: integrators/registry.cpp holds the table
// (docs/options-design.md).
#include <memory>
#include <string>
#include <vector>

#include "core/integrator.h"
#include "core/options.h"

namespace tray {

using IntegratorFactory = std::unique_ptr<Integrator> (*)(const RenderContext&);

/// One integrator: everything the command line, validation, the farm job signature and the
/// EXR metadata need to know about it.
struct IntegratorEntry {
  std::string name;
  std::string description;
  IntegratorFactory create = nullptr;
  /// Its own options, declared beside its code (e.g. whittedOptions() in whitted.cpp).
  std::vector<OptionSpec> options;
  /// A wrapping integrator: the option that names the integrator it wraps (adaptive: "inner"),
  /// whose options then apply too. Empty for the others.
  std::string innerOption;
  /// Unlit surfaces (KHR_materials_unlit) light the scene: paths that bounce off a surface and
  /// find one carry its colour, as from an emitter. Then an unlit sky box around the camera is
  /// the scene's light (render/render_setup.h useUnlitEnclosureAsLight).
  bool unlitSurfacesLight = false;
};

/// The registry: one line per built-in integrator in integrators/registry.cpp, then any added
/// by registerIntegrator.
const std::vector<IntegratorEntry>& integratorRegistry();
/// Adds an integrator that is not in the table (a test's toy integrator, a program embedding
/// TRay). Call it before building the command line or rendering, not while rendering; throws
/// tray::Error if the name is taken.
void registerIntegrator(IntegratorEntry entry);
/// The entry named `name`; throws tray::Error naming the choices for an unknown name.
const IntegratorEntry& findIntegrator(const std::string& name);

/// Whether the integrator `settings` names (through the ones it wraps) lights the scene from
/// unlit surfaces (IntegratorEntry::unlitSurfacesLight).
bool unlitSurfacesLight(const RenderSettings& settings);

/// `settings` with the options of its integrator (settings "integrator", or `name` if given)
/// and of the integrators it wraps declared: exactly the options that render reads.
RenderSettings withIntegratorOptions(const RenderSettings& settings, const std::string& name = "");
/// Checks, before anything renders, the integrator names and every value set against each
/// spec of its name (render-wide or of any integrator); throws tray::Error
/// "--aa-depth 13: expected 0..12", or "unknown option --name" for a name nobody declares.
void validateOptions(const RenderSettings& settings);

/// One warning per option set in `settings` that its render does not read: declared only by
/// integrators other than the chosen one and those it wraps ("--clamp-indirect has no effect
/// with --integrator whitted (an option of path, path-scalar, path-wavefront)"). Not an error:
/// a farm or a script may pass one set of options to every integrator.
std::vector<std::string> unusedOptionWarnings(const RenderSettings& settings);

/// Creates the integrator named ctx.settings "integrator" (or `name` if given) with its options
/// declared and validated; throws tray::Error for an unknown name or an invalid value.
std::unique_ptr<Integrator> makeIntegrator(const RenderContext& ctx, const std::string& name = "");

}  // namespace tray

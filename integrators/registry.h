#pragma once
// The integrator plugins by name: integrators/registry.cpp holds the table.
#include <memory>
#include <string>
#include <vector>

#include "core/integrator.h"

namespace tray {

using IntegratorFactory = std::unique_ptr<Integrator> (*)(const RenderContext&);

struct IntegratorEntry {
  const char* name;
  const char* description;
  IntegratorFactory create;
};

/// The registry: one line per integrator in integrators/registry.cpp.
const std::vector<IntegratorEntry>& integratorRegistry();
/// Creates the integrator named ctx.settings.integrator (or `name` if given); throws
/// tray::Error naming the choices for an unknown name.
std::unique_ptr<Integrator> makeIntegrator(const RenderContext& ctx, const std::string& name = "");

}  // namespace tray

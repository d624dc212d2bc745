#include "integrators/registry.h"

#include "core/error.h"
#include "integrators/adaptive.h"
#include "integrators/path.h"
#include "integrators/whitted.h"

namespace tray {

// The integrator table: a new integrator is one file plus one line here.
const std::vector<IntegratorEntry>& integratorRegistry() {
  static const std::vector<IntegratorEntry> table = {
      {"whitted", "recursive ray tracing: Phong, shadows, mirror reflection, refraction",
       makeWhitted},
      {"adaptive", "adaptive supersampling around --inner: corners, subdivide where they differ", makeAdaptive},
      {"path", "path tracing: MIS next-event estimation, GGX/dielectric BSDFs, area lights", makePath},
  };
  return table;
}

std::unique_ptr<Integrator> makeIntegrator(const RenderContext& ctx, const std::string& name) {
  const std::string& wanted = name.empty() ? ctx.settings.integrator : name;
  for (const auto& e : integratorRegistry())
    if (wanted == e.name) return e.create(ctx);
  std::string known;
  for (const auto& e : integratorRegistry())
    known += std::string(known.empty() ? "" : ", ") + e.name;
  throw Error("unknown integrator '" + wanted + "' (known: " + known + ")");
}

}  // namespace tray

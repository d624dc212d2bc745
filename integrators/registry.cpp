#include "integrators/adaptive.h"
#include "integrators/integrator.h"
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

}  // namespace tray

#pragma once
// The speed-against-accuracy sweep behind `tray-bench sweep`: renders a scene with many methods
// and settings and measures time, rays and error against a converged reference.
#include <string>
#include <vector>

#include "core/integrator.h"

namespace tray {

/// One render configuration; `method` names the line it belongs to on the charts.
struct SweepConfig {
  std::string method;
  std::string setting;  ///< the varying parameter, e.g. "spp=16"
  RenderSettings settings;
  std::string accel = "embree";
  int threads = 0;
};

/// The standard sweep for the integrators and accelerators that are registered.
std::vector<SweepConfig> standardSweep(const std::vector<std::string>& accels,
                                       const std::vector<int>& threads, int maxSpp);

/// The settings that define an integrator's converged reference.
RenderSettings referenceSettings(const std::string& integrator, int referenceSpp);

}  // namespace tray

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

/// Where a scene's converged reference of an integrator family ("path" or "whitted") at w x h
/// is cached in `outDir`: one name, so that every benchmark that renders it finds it.
std::string referencePath(const std::string& outDir, const std::string& scenePath,
                          const std::string& family, int width, int height);

}  // namespace tray

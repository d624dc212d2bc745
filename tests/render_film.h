#pragma once
// Renders a scene built in code into a Film: the set-up every render test repeats.
#include <string>
#include <vector>

#include "render/prepared_scene.h"

namespace tray::test {

/// Renders `scene` through `cam` with the settings' integrator on `accelerator`; threads 0 = all
/// cores. `stats`, when not null, receives the render's counters.
inline Film renderFilm(const Scene& scene, const CameraDesc& cam, int w, int h,
                       const RenderSettings& settings, RenderStats* stats = nullptr,
                       const std::vector<std::string>& aovs = {},
                       const std::string& accelerator = "embree", int threads = 0) {
  RenderOptions options;
  options.aovs = aovs;
  options.threads = threads;
  return PreparedScene(scene, cam, {w, h}, accelerator).render(settings, options, stats);
}

}  // namespace tray::test

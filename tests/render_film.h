#pragma once
// Renders a scene built in code into a Film: the set-up every render test repeats.
#include <string>
#include <vector>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "render/renderer.h"
#include "core/integrator.h"
#include "integrators/registry.h"

namespace tray::test {

/// Renders `scene` through `cam` with the settings' integrator on `accelerator`; threads 0 = all
/// cores. `stats`, when not null, receives the render's counters.
inline Film renderFilm(const Scene& scene, const CameraDesc& cam, int w, int h,
                       const RenderSettings& settings, RenderStats* stats = nullptr,
                       const std::vector<std::string>& aovs = {},
                       const std::string& accelerator = "embree", int threads = 0) {
  auto camera = Camera::create(cam, w, h);
  auto accel = makeAccelerator(accelerator, scene);
  RenderContext ctx{scene, *accel, *camera, settings, w, h};
  auto integrator = makeIntegrator(ctx);
  Film film(w, h);
  RenderOptions options;
  options.aovs = aovs;
  options.threads = threads;
  RenderStats st = renderImage(*integrator, film, options);
  if (stats) *stats = st;
  return film;
}

}  // namespace tray::test

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

/// The mean beauty of a film, every pixel alike.
inline Color meanBeauty(const Film& f) {
  double sum[3] = {0, 0, 0};
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x)
      for (int c = 0; c < 3; ++c) sum[c] += f.pixel(Film::kBeauty, x, y)[c];
  const double n = double(f.width()) * f.height();
  return Color(float(sum[0] / n), float(sum[1] / n), float(sum[2] / n));
}

}  // namespace tray::test

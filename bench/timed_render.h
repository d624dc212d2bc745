#pragma once
// One render of a scene's first camera through tests/render_film.h, timed in CPU seconds
// (bench/cpu_time.h): what the light and triangle sampling benchmarks each render their
// settings with.
#include "bench/cpu_time.h"
#include "tests/render_film.h"

namespace tray {

struct TimedFilm {
  Film film{1, 1};
  double seconds = 0;  ///< CPU seconds of the render, every thread's
};

/// `settings` rendered at width x height from scene.cameras[0] on Embree with `threads`.
inline TimedFilm timedRender(const Scene& scene, int width, int height,
                             const RenderSettings& settings, int threads) {
  TimedFilm r;
  const double t0 = cpuSeconds();
  r.film = test::renderFilm(scene, scene.cameras.at(0), width, height, settings, nullptr, {},
                            "embree", threads);
  r.seconds = cpuSeconds() - t0;
  return r;
}

}  // namespace tray

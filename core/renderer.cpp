#include "core/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <mutex>

#include "core/aov.h"
#include "core/cryptomatte.h"

namespace tray {

RenderStats renderImage(const Integrator& integrator, Film& film, const RenderOptions& options) {
  const int ts = std::max(1, options.tileSize);
  const int tilesX = (film.width() + ts - 1) / ts, tilesY = (film.height() + ts - 1) / ts;
  const int tileCount = tilesX * tilesY;
  RenderStats result;
  const AovSet aovs(film, options.aovs);
  const Cryptomatte crypto(film, integrator.context().scene, options.aovs, options.cryptomatteRanks);
  std::mutex mutex;
  int tilesDone = 0;
  auto start = std::chrono::steady_clock::now();

  auto renderTile = [&](int tile) {
    RayStats local;
    IdCoverage coverage;  // reused across the tile's pixels; only filled for Cryptomatte
    int x0 = (tile % tilesX) * ts, y0 = (tile / tilesX) * ts;
    int x1 = std::min(x0 + ts, film.width()), y1 = std::min(y0 + ts, film.height());
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        coverage.clear();
        PixelValue v = integrator.renderPixel(x, y, local, crypto.active() ? &coverage : nullptr);
        float* px = film.pixel(Film::kBeauty, x, y);
        px[0] = v.radiance.x, px[1] = v.radiance.y, px[2] = v.radiance.z, px[3] = v.alpha;
        aovs.write(film, x, y, v);
        if (crypto.active()) crypto.write(film, x, y, coverage);
      }
    std::lock_guard<std::mutex> lock(mutex);
    result.rays += local;
    ++tilesDone;
    if (options.onProgress) options.onProgress(double(tilesDone) / tileCount);
  };

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tileCount, 1), [&](const tbb::blocked_range<int>& r) {
      for (int t = r.begin(); t != r.end(); ++t) renderTile(t);
    });
  });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace tray

#pragma once
// A whole render of a Scene built in code, for the path-tracer tests that compare two drivers
// pixel by pixel (tests/integrators/path_wavefront_test.cpp, matte_batch_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "render/prepared_scene.h"

namespace tray::test {

struct Render {
  Film film{1, 1};
  RenderStats stats;
};

struct Job {
  std::string integrator = "path-scalar";  ///< the reference; `path` runs the wavefront
  std::string inner;                       ///< adaptive's inner integrator, when set
  std::string accel = "embree";
  std::string sampler = "sobol";
  int size = 24, spp = 8, threads = 1, tileSize = 16;
  uint64_t seed = 0;
  std::vector<std::string> aovs;
  std::optional<SampleRange> samples;         ///< none: every sample
  std::optional<SamplingPasses> passes;       ///< set: rendered in passes (adaptive, time limit)
  int x0 = 0, y0 = 0, width = 0, height = 0;  ///< a region (width 0: the whole image)
  /// Called with each checkpoint when set (checkpointSeconds > 0).
  double checkpointSeconds = 0;
  std::function<void(const Film&, const RenderState&)> onCheckpoint;
  const std::atomic<bool>* stop = nullptr;
};

/// `state` (when given) is resumed and receives the render's state; `film` (when given) is the
/// film a resumed render goes on with (a checkpoint's).
inline Render render(const Scene& scene, const Job& job, RenderState* state = nullptr,
                     const Film* film = nullptr) {
  const PreparedScene prepared(scene, chooseCamera(scene, -1), {job.size, job.size}, job.accel);
  RenderSettings settings;
  settings.set("integrator", job.integrator);
  if (!job.inner.empty()) settings.set("inner", job.inner);
  settings.set("spp", job.spp);
  settings.set("sampler", job.sampler);
  settings.set("seed", int64_t(job.seed));
  auto integrator = prepared.integrator(settings);
  Render r;
  r.film = film ? *film : job.width > 0 ? Film(job.width, job.height) : Film(job.size, job.size);
  RenderOptions options;
  options.x0 = job.x0, options.y0 = job.y0;
  options.passes = job.passes;
  options.checkpointSeconds = job.checkpointSeconds;
  options.onCheckpoint = job.onCheckpoint;
  options.stop = job.stop;
  options.threads = job.threads;
  options.tileSize = job.tileSize;
  options.aovs = job.aovs;
  options.samples = job.samples;
  RenderState fresh;
  r.stats = renderImage(*integrator, r.film, state ? *state : fresh, options);
  return r;
}

/// Every layer, every channel, every pixel: the number of values that differ.
inline size_t differingValues(const Film& a, const Film& b) {
  EXPECT_EQ(a.layers().size(), b.layers().size());
  size_t differ = 0;
  for (size_t l = 0; l < std::min(a.layers().size(), b.layers().size()); ++l) {
    EXPECT_EQ(a.layers()[l].name, b.layers()[l].name);
    const auto &da = a.layers()[l].data, &db = b.layers()[l].data;
    EXPECT_EQ(da.size(), db.size());
    for (size_t i = 0; i < std::min(da.size(), db.size()); ++i)
      differ += !(da[i] == db[i] || (std::isnan(da[i]) && std::isnan(db[i])));
  }
  return differ;
}

}  // namespace tray::test

#pragma once
// A whole render of a Scene built in code, for the path-tracer tests that compare two drivers
// pixel by pixel (tests/integrators/path_wavefront_test.cpp, matte_batch_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  std::optional<SampleRange> samples;  ///< none: every sample
};

inline Render render(const Scene& scene, const Job& job, RenderState* state = nullptr) {
  const PreparedScene prepared(scene, chooseCamera(scene, -1), {job.size, job.size}, job.accel);
  RenderSettings settings;
  settings.set("integrator", job.integrator);
  if (!job.inner.empty()) settings.set("inner", job.inner);
  settings.set("spp", job.spp);
  settings.set("sampler", job.sampler);
  settings.set("seed", int64_t(job.seed));
  auto integrator = prepared.integrator(settings);
  Render r;
  r.film = Film(job.size, job.size);
  RenderOptions options;
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

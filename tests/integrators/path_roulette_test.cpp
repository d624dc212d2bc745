// Russian roulette (Arvo & Kirk 1990) keeps the path tracer unbiased for every --rr-depth and
// --rr-survival: a closed form where roulette decides most paths. Inside a closed box whose walls
// all emit E and reflect a diffuse albedo a, every direction sees the same radiance; a path of
// --max-depth D gathers one term per segment, so every pixel is E (1 - a^D) / (1 - a).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tests/integrators/path_under_test.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr float kAlbedo = 0.8f, kEmission = 0.1f;
constexpr int kMaxDepth = 8;

/// The box [-1, 1]^3, every wall emissive and diffuse on both sides (the camera is inside).
Scene glowingBox() {
  Scene s;
  Material m = diffuse(Color(kAlbedo));
  m.emissive = Color(kEmission);
  m.doubleSided = true;
  TriangleMesh box;
  for (int i = 0; i < 8; ++i)
    box.positions.push_back({i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f});
  // Two triangles per face, the corners of each face in order around it.
  const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                           {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (const auto& f : faces)
    for (int k : {0, 1, 2, 0, 2, 3}) box.indices.push_back(uint32_t(f[k]));
  box.material = addMaterial(s, m);
  addMeshInstance(s, addMesh(s, box), Mat4::identity());
  s.finalize();
  return s;
}

struct Roulette {
  int depth;
  std::string survival;
};

/// The mean of the pixels and the rays traced after the camera rays.
std::pair<double, uint64_t> render(const Roulette& r) {
  RenderSettings st;
  st.set("integrator", pathUnderTest());
  st.set("spp", 256);
  st.set("max-depth", kMaxDepth);
  st.set("rr-depth", r.depth);
  st.set("rr-survival", r.survival);
  RenderStats stats;
  const Film f = renderFilm(glowingBox(), lookAt({0.2f, 0.1f, 0.3f}, {1, 0.4f, -1}, 1.2f), 12,
                            12, st, &stats, {}, "embree", 0);
  double sum = 0;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 12; ++x) sum += f.pixel(Film::kBeauty, x, y)[1];
  EXPECT_EQ(stats.rays.nanSamples, 0u);
  return {sum / 144, stats.rays.secondaryRays};
}

TEST(Roulette, EveryDepthAndSurvivalRuleMeetsTheGeometricSeries) {
  const double expected = kEmission * (1 - std::pow(kAlbedo, kMaxDepth)) / (1 - kAlbedo);
  const auto [none, allRays] = render({1000, "sqrt"});  // no roulette within the depth
  EXPECT_NEAR(none, expected, 0.005 * expected);
  for (const Roulette& r : {Roulette{0, "sqrt"}, Roulette{0, "throughput"},
                            Roulette{3, "throughput"}, Roulette{5, "sqrt"}}) {
    const auto [mean, rays] = render(r);
    // 36864 paths: unbiased, within 0.1% here; survivors not divided by their probability
    // (a biased rule) are 10-43% off.
    EXPECT_NEAR(mean, expected, 0.005 * expected) << r.depth << " " << r.survival;
    EXPECT_LT(rays, allRays) << "roulette ended no path: " << r.depth << " " << r.survival;
  }
  // The square root keeps more paths than the throughput itself at the same depth.
  EXPECT_GT(render({0, "sqrt"}).second, render({0, "throughput"}).second);
}

}  // namespace
}  // namespace tray

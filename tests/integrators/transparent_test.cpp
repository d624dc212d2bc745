// --transparent: camera rays that escape give RGBA 0 while the environment still lights the
// scene, so the beauty is premultiplied and "over" a backdrop equal to the environment gives
// back the opaque render. Whitted, path and adaptive all go through Integrator::cameraLi.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr int kSize = 24;

/// A grey sphere over a constant environment of 1: the environment is its only light.
Scene sphereInWhiteSky() {
  Scene s;
  Material m = diffuse(Color(0.5f));
  m.phong.ambient = Color(0.5f);  // Whitted: lit by the ambient term of the environment
  addSphere(s, Vec3(0.0f), 1.0f, addMaterial(s, m));
  s.environment.ambient = Color(1.0f);
  s.environment.background = Color(1.0f);
  s.finalize();
  return s;
}

Film render(const Scene& s, const std::string& integrator, bool transparent,
            const std::string& accel = "embree") {
  RenderSettings st;
  st.set("integrator", integrator);
  st.set("spp", 16);
  st.set("transparent", transparent);
  if (integrator == "adaptive") st.set("inner", "path");
  return renderFilm(s, lookAt(Vec3(0, 0, 4), Vec3(0.0f)), kSize, kSize, st, nullptr, {}, accel);
}

class Transparent : public ::testing::TestWithParam<const char*> {};

TEST_P(Transparent, EscapedRaysAreZeroSurfacesUnchangedEdgesPremultiplied) {
  const Scene s = sphereInWhiteSky();
  const Film opaque = render(s, GetParam(), false), clear = render(s, GetParam(), true);
  const bool whitted = std::string(GetParam()) == "whitted";
  int sky = 0, interior = 0, edges = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const float* o = opaque.pixel(Film::kBeauty, x, y);
      const float* c = clear.pixel(Film::kBeauty, x, y);
      EXPECT_EQ(o[3], c[3]) << "alpha is coverage either way, at " << x << "," << y;
      if (c[3] == 0) {  // only sky: RGBA exactly 0 (the opaque render shows the sky, 1)
        ++sky;
        for (int k = 0; k < 4; ++k) EXPECT_EQ(c[k], 0.0f) << x << "," << y;
        EXPECT_NEAR(o[0], 1.0f, 1e-6f);
      } else if (c[3] == 1) {  // only sphere: the same bits
        ++interior;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(o[k], c[k]) << x << "," << y;
      } else {
        // Partly covered: the sky's share is gone from RGB, so "over" a backdrop equal to the
        // environment (1) gives the opaque pixel back: C + (1 - alpha) x 1. RGB / alpha is
        // the radiance of the surface alone: Whitted's is the ambient term, 0.5 x 1, exactly.
        ++edges;
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(c[k] + (1 - c[3]) * 1.0f, o[k], 2e-5f) << x << "," << y;
          if (whitted) {
            EXPECT_NEAR(c[k] / c[3], 0.5f, 1e-5f) << x << "," << y;
          }
          EXPECT_GT(c[k], 0.0f) << x << "," << y;
        }
      }
    }
  EXPECT_GT(sky, 100);
  EXPECT_GT(interior, 50);
  if (std::string(GetParam()) != "adaptive") {
    EXPECT_GT(edges, 10);  // 16 samples per pixel: the sphere's outline is partly covered
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, Transparent,
                         ::testing::Values("whitted", "path", "adaptive"));

TEST(Transparent, ReflectionsOfTheEnvironmentStay) {
  // A mirror sphere reflects the white sky: its pixels keep that light with --transparent.
  Scene s;
  Material mirror = diffuse(Color(0.0f));
  mirror.hasPhong = true;
  mirror.phong.reflectance = 1.0f;
  addSphere(s, Vec3(0.0f), 1.0f, addMaterial(s, mirror));
  s.environment.background = Color(1.0f);
  s.finalize();
  const Film f = render(s, "whitted", true);
  const float* centre = f.pixel(Film::kBeauty, kSize / 2, kSize / 2);
  EXPECT_EQ(centre[3], 1.0f);
  EXPECT_NEAR(centre[0], 1.0f, 1e-5f);
}

TEST(Transparent, EnvironmentFlagDoesTheSame) {
  Scene s = sphereInWhiteSky();
  const Film byOption = render(s, "path", true);
  s.environment.transparent = true;  // TRAY_environment {"transparent": true}
  const Film byScene = render(s, "path", false);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int k = 0; k < 4; ++k)
        EXPECT_EQ(byOption.pixel(Film::kBeauty, x, y)[k], byScene.pixel(Film::kBeauty, x, y)[k]);
}

TEST(Transparent, EmbreeAndBvhAgree) {
  const Scene s = sphereInWhiteSky();
  const Film a = render(s, "path", true, "embree"), b = render(s, "path", true, "bvh");
  int differ = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      differ += a.pixel(Film::kBeauty, x, y)[3] != b.pixel(Film::kBeauty, x, y)[3];
  EXPECT_LE(differ, 2);  // the two may disagree on a grazing ray or two, never on the image
}

}  // namespace
}  // namespace tray

#include "film/aov.h"

#include <gtest/gtest.h>

#include "accel/registry.h"
#include "core/error.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

TEST(Aov, ParsesListsAndRejectsUnknownNames) {
  EXPECT_EQ(AovSet::parse("depth,normal"), (std::vector<std::string>{"depth", "normal"}));
  // "all": every layer but the seven light-path ones, which only the path tracer fills.
  EXPECT_EQ(AovSet::parse("all").size(), AovSet::known().size() - kLightPathCount);
  EXPECT_EQ(AovSet::parse("albedo,lightpaths").size(), size_t(1 + kLightPathCount));
  // A render whose integrator splits light paths: "all" means all, the light paths included
  // (once, also when named beside it); lists without "all" are as they were.
  EXPECT_EQ(AovSet::parse("all", true).size(), AovSet::known().size());
  EXPECT_EQ(AovSet::parse("all,lightpaths", true).size(), AovSet::known().size());
  EXPECT_EQ(AovSet::parse("depth", true), (std::vector<std::string>{"depth"}));
  EXPECT_EQ(AovSet::parse("all", false).size(), AovSet::known().size() - kLightPathCount);
  EXPECT_EQ(AovSet::parse("specular_indirect"), (std::vector<std::string>{"specular_indirect"}));
  EXPECT_THROW(AovSet::parse("depth,colour"), Error);
}

TEST(Aov, LayersHoldDepthNormalAndIdsOfTheFirstHit) {
  // A floor plane at y = 0 and a unit sphere at (0, 1, -4), seen by a camera at the origin
  // looking down -Z from height 1.
  Scene s;
  int floorMat = addMaterial(s, diffuse(Color(0.2f)));
  int ballMat = addMaterial(s, diffuse(Color(0.9f, 0.5f, 0.1f)));
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), floorMat);
  addSphere(s, {0, 1, -4}, 1.0f, ballMat);
  s.finalize();
  CameraDesc cd = lookAt({0, 1, 0}, {0, 1, -1}, 1.0f);
  const int W = 33, H = 33;
  const PreparedScene prepared(s, cd, {W, H});
  const RenderContext ctx = prepared.context(RenderSettings{});
  auto integrator = makeIntegrator(ctx);
  Film film(W, H);
  RenderOptions opt;
  opt.aovs = AovSet::parse("all");
  renderImage(*integrator, film, opt);

  int Z = film.findLayer("Z"), N = film.findLayer("N"), obj = film.findLayer("objectid"),
      mat = film.findLayer("materialid"), P = film.findLayer("P"), spp = film.findLayer("samples");
  ASSERT_GE(Z, 0);
  ASSERT_GE(N, 0);
  // Centre pixel: the sphere's front point (0, 1, -3), normal +Z, depth 3.
  EXPECT_NEAR(film.pixel(Z, 16, 16)[0], 3.0f, 1e-4f);
  EXPECT_NEAR(film.pixel(N, 16, 16)[2], 1.0f, 1e-4f);
  EXPECT_NEAR(film.pixel(P, 16, 16)[2], -3.0f, 1e-4f);
  EXPECT_EQ(film.pixel(obj, 16, 16)[0], 1.0f);
  EXPECT_EQ(film.pixel(mat, 16, 16)[0], float(ballMat));
  EXPECT_EQ(film.pixel(spp, 16, 16)[0], 1.0f);
  // Bottom-centre pixel: the floor, normal +Y, depth from the pixel's ray.
  Ray r = prepared.camera().generateRay(16.5f, 32.5f);
  float t = -r.o.y / r.d.y;
  EXPECT_NEAR(film.pixel(Z, 16, 32)[0], t * length(r.d), 1e-3f);
  EXPECT_NEAR(film.pixel(N, 16, 32)[1], 1.0f, 1e-5f);
  EXPECT_EQ(film.pixel(obj, 16, 32)[0], 0.0f);
  // Top row sees the sky: infinite depth, no object.
  EXPECT_EQ(film.pixel(Z, 16, 0)[0], kInfinity);
  EXPECT_EQ(film.pixel(obj, 16, 0)[0], -1.0f);
  EXPECT_EQ(film.pixel(Film::kBeauty, 16, 0)[3], 0.0f);  // alpha = coverage
}

TEST(Aov, AlbedoNormalAndDepthAverageEverySampleWithThePixelFilter) {
  // A sphere of one albedo over nothing: in an outline pixel a fraction alpha of the (filter-
  // weighted) samples hit it, so the averaged albedo is alpha x its albedo, and the normal is
  // alpha x the mean normal of the hits (length <= alpha). The depth averages the hits only.
  Scene s;
  const Color a(0.9f, 0.5f, 0.1f);
  addSphere(s, {0, 0, -4}, 1.0f, addMaterial(s, diffuse(a)));
  s.finalize();
  for (const char* filter : {"box", "gaussian"}) {
    RenderSettings st;
    st.set("spp", 64);
    st.set("pixel-sampler", "jitter");
    st.set("filter", filter);
    const int W = 24;
    Film film = renderFilm(s, lookAt({0, 0, 0}, {0, 0, -1}, 0.6f), W, W, st, nullptr,
                           AovSet::parse("albedo,normal,depth"));
    const int albedo = film.findLayer("albedo"), N = film.findLayer("N"), Z = film.findLayer("Z");
    int outline = 0;
    for (int y = 0; y < W; ++y)
      for (int x = 0; x < W; ++x) {
        const float alpha = film.pixel(Film::kBeauty, x, y)[3];
        const float* al = film.pixel(albedo, x, y);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(al[c], alpha * a[c], 1e-5f) << x << "," << y;
        const float* n = film.pixel(N, x, y);
        EXPECT_LE(length(Vec3(n[0], n[1], n[2])), alpha + 1e-5f);
        const float z = film.pixel(Z, x, y)[0];
        if (alpha == 0) {
          EXPECT_EQ(z, kInfinity);
        } else {
          EXPECT_GE(z, 3.0f - 1e-4f);  // between the sphere's nearest point and its outline
          EXPECT_LE(z, std::sqrt(15.0f) + 1e-4f);
        }
        if (alpha > 0.05f && alpha < 0.95f) ++outline;
      }
    EXPECT_GT(outline, 8) << filter;  // the outline pixels are mixes, not one sample's value
  }
}

}  // namespace
}  // namespace tray

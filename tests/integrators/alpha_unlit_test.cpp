// Closed-form checks of alphaMode BLEND (stochastic in the path tracer, a straight blend in
// Whitted) and of KHR_materials_unlit, in both integrators.
#include <gtest/gtest.h>

#include <cmath>

#include "gltf/gltf_loader.h"
#include "render/render_setup.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

/// Camera straight down onto the quads (narrow field: every pixel sees both).
const CameraDesc kCamera = lookAt({0, 4, 0}, {0, 0, 0}, 0.3f);

/// A black BLEND quad of coverage `alpha` at y = 0 over an emitter of radiance 1 at y = -1,
/// black background, no other light.
Scene blendOverEmitter(float alpha) {
  Scene s;
  Material blend = diffuse(Color(0.0f));
  blend.alphaMode = AlphaMode::kBlend;
  blend.alpha = alpha;
  addMeshInstance(s, addMesh(s, quadMesh(1.0f, addMaterial(s, blend))), Mat4::identity());
  Material light = diffuse(Color(0.0f));
  light.emissive = Color(1.0f);
  addMeshInstance(s, addMesh(s, quadMesh(4.0f, addMaterial(s, light))),
                  Mat4::translate({0, -1, 0}));
  s.finalize();
  return s;
}

Color mean(const Film& f, int w, int h) {
  Color sum(0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* p = f.pixel(Film::kBeauty, x, y);
      sum += Color(p[0], p[1], p[2]);
    }
  return sum / float(w * h);
}

TEST(AlphaBlend, PathTracerTransmitsOneMinusAlphaOnAverage) {
  const Scene s = blendOverEmitter(0.25f);
  RenderSettings st;
  st.set("integrator", std::string("path"));
  st.set("spp", 64);
  for (const char* accel : {"embree", "bvh"}) {
    const Film f = renderFilm(s, kCamera, 16, 16, st, nullptr, {}, accel);
    // N = 16 x 16 x 64 = 16384 camera samples, each 1 (passed) or 0 (stopped by the black
    // surface): sigma = sqrt(0.75 x 0.25 / N) = 0.0034; tolerance 4 sigma.
    const Color m = mean(f, 16, 16);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], 0.75f, 0.0135f) << accel;
  }
}

TEST(AlphaBlend, WhittedBlendsStraight) {
  const Scene s = blendOverEmitter(0.25f);
  RenderSettings st;
  st.set("integrator", std::string("whitted"));
  const Film f = renderFilm(s, kCamera, 8, 8, st);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(f.pixel(Film::kBeauty, x, y)[c], 0.75f, 1e-5f);
}

TEST(AlphaBlend, WhittedShadowsPassOneMinusAlpha) {
  // A white floor lit by a point light straight above, a BLEND sheet of alpha 0.25 between.
  Scene s;
  addMeshInstance(s, addMesh(s, quadMesh(4.0f, addMaterial(s, diffuse(Color(1.0f))))),
                  Mat4::identity());
  Material sheet = diffuse(Color(0.0f));
  sheet.alphaMode = AlphaMode::kBlend;
  sheet.alpha = 0.25f;
  addMeshInstance(s, addMesh(s, quadMesh(4.0f, addMaterial(s, sheet))),
                  Mat4::translate({0, 2, 0}));
  s.lights.push_back(pointLight({0, 3, 0}, Color(9.0f)));
  s.finalize();
  RenderSettings st;
  st.set("integrator", std::string("whitted"));
  // The camera sits below the sheet, so only the shadow rays cross it.
  const Film f = renderFilm(s, lookAt({0, 1.5f, 0}, {0, 0, 0}, 0.02f), 2, 2, st);
  // Lambert floor under E = 9 / 3^2 = 1 at normal incidence: L = 1/pi, times 0.75.
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(f.pixel(Film::kBeauty, 0, 0)[c], 0.75f / float(M_PI), 2e-3f);
}

TEST(AlphaMask, EmbreeAndBvhRenderTheSameCoverage) {
  // A MASK quad whose 2 x 1 texture is opaque on the left, clear on the right, beside a BLEND
  // quad of alpha 0.5: the film's alpha (camera-ray coverage) must match pixel for pixel.
  Scene s;
  TextureImage split;
  split.width = 2;
  split.height = 1;
  split.pixels.assign(6, 1.0f);
  split.alpha = {1.0f, 0.0f};
  s.textures.push_back(split);
  Material mask = diffuse(Color(0.5f));
  mask.alphaMode = AlphaMode::kMask;
  mask.baseColorTexture.image = 0;
  mask.baseColorTexture.wrapS = TextureWrap::kClampToEdge;
  TriangleMesh q = quadMesh(1.0f, addMaterial(s, mask));
  for (const Vec3& p : q.positions) q.uvs.push_back({(p.x + 1) / 2, (p.z + 1) / 2});
  addMeshInstance(s, addMesh(s, q), Mat4::translate({-1.1f, 0, 0}));
  Material blend = diffuse(Color(0.5f));
  blend.alphaMode = AlphaMode::kBlend;
  blend.alpha = 0.5f;
  addMeshInstance(s, addMesh(s, quadMesh(1.0f, addMaterial(s, blend))),
                  Mat4::translate({1.1f, 0, 0}));
  s.lights.push_back(pointLight({0, 3, 0}, Color(5.0f)));
  s.finalize();
  RenderSettings st;
  st.set("integrator", std::string("path"));
  st.set("spp", 4);
  const CameraDesc cam = lookAt({0, 5, 0}, {0, 0, 0}, 0.9f);
  const Film a = renderFilm(s, cam, 48, 24, st, nullptr, {}, "embree");
  const Film b = renderFilm(s, cam, 48, 24, st, nullptr, {}, "bvh");
  double covered = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 48; ++x) {
      EXPECT_EQ(a.pixel(Film::kBeauty, x, y)[3], b.pixel(Film::kBeauty, x, y)[3]) << x << "," << y;
      covered += a.pixel(Film::kBeauty, x, y)[3];
    }
  EXPECT_GT(covered, 10.0);
}

TEST(Unlit, ShowsBaseColourTimesVertexColourWithoutLighting) {
  Scene s;
  Material m;
  m.baseColor = {0.2f, 0.4f, 0.6f};
  m.unlit = true;
  TriangleMesh q = quadMesh(1.0f, addMaterial(s, m));
  q.colors.assign(4, Color(0.5f, 1.0f, 1.0f));
  addMeshInstance(s, addMesh(s, q), Mat4::identity());
  s.lights.push_back(pointLight({0, 3, 0}, Color(100.0f)));  // ignored by unlit surfaces
  s.environment.background = Color(0.3f);
  s.finalize();
  for (const char* integrator : {"path", "whitted"}) {
    RenderSettings st;
    st.set("integrator", std::string(integrator));
    st.set("spp", 4);
    const Film f = renderFilm(s, kCamera, 4, 4, st);
    const Color expected{0.1f, 0.4f, 0.6f};
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(f.pixel(Film::kBeauty, x, y)[c], expected[c], 1e-5f) << integrator;
  }
}

}  // namespace
}  // namespace tray

namespace tray {
namespace {

TEST(AlphaSharedSamples, EmbreeAndBvhSeeTheSameCoverageOnEveryAlphaAsset) {
  // The shared Khronos assets that use alphaMode MASK or BLEND, as loaded from their files:
  // the camera rays' coverage (film alpha, 4 spp) is identical on Embree and the BVH.
  const std::string shared = TRAY_SHARED_DIR;
  for (const std::string file : {"/gltf-features/AlphaBlendModeTest.glb",
                                 "/gltf-samples/TransmissionTest.glb"}) {
    Scene s = loadGltf(shared + file);
    const CameraDesc cam = chooseCamera(s, -1);
    addDefaultLightingIfUnlit(s, cam);
    RenderSettings st;
    st.set("integrator", std::string("path"));
    st.set("spp", 4);
    const Film a = test::renderFilm(s, cam, 64, 48, st, nullptr, {}, "embree");
    const Film b = test::renderFilm(s, cam, 64, 48, st, nullptr, {}, "bvh");
    int differing = 0, covered = 0;
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x) {
        const float ca = a.pixel(Film::kBeauty, x, y)[3], cb = b.pixel(Film::kBeauty, x, y)[3];
        differing += ca != cb;
        covered += ca > 0;
      }
    EXPECT_EQ(differing, 0) << file;
    EXPECT_GT(covered, 64 * 48 / 10) << file;
  }
}

}  // namespace
}  // namespace tray

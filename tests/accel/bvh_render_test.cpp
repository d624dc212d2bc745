// Same images: every scene in scenes/ and every shared glTF sample rendered with Embree and with
// the in-house BVH. Whitted renders agree within RMSE 1e-5 with no pixel off by more than 1e-3;
// path renders (same seed, so the same random numbers) agree in mean within 0.1%.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "tests/film_difference.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sceneFiles() {
  std::vector<std::string> files;
  auto add = [&](const fs::path& dir, bool recurse) {
    if (!fs::exists(dir)) return;
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.is_directory() && recurse && e.path().filename() != "invalid") {
        for (const auto& f : fs::directory_iterator(e.path()))
          if (f.path().extension() == ".gltf" || f.path().extension() == ".glb")
            files.push_back(f.path().string());
      } else if (e.path().extension() == ".gltf" || e.path().extension() == ".glb") {
        files.push_back(e.path().string());
      }
    }
  };
  add(fs::path(TRAY_SOURCE_DIR) / "scenes", false);
  add(fs::path(TRAY_SHARED_DIR) / "gltf-samples", true);
  // alphaMode MASK and BLEND (issue 15): Embree's filter callbacks against the BVH's own test.
  files.push_back(
      (fs::path(TRAY_SHARED_DIR) / "gltf-features" / "AlphaBlendModeTest.glb").string());
  std::sort(files.begin(), files.end());
  return files;
}

/// Whitted shows nothing without lights: give unlit samples a point light at the camera, so
/// their images test the accelerators too.
Scene withHeadlight(Scene scene) {
  if (!scene.lights.empty()) return scene;
  CameraDesc cam = chooseCamera(scene, -1);
  Vec3 eye = cam.toWorld.point(Vec3(0.0f));
  float d2 = lengthSquared(scene.bounds().center() - eye);
  scene.lights.push_back(test::pointLight(eye, Color(2.0f * std::max(d2, 1e-4f))));
  return scene;
}

Film render(const Scene& scene, const std::string& accelName, RenderSettings settings, int w,
            int h) {
  CameraDesc cam = chooseCamera(scene, -1);
  const PreparedScene prepared(scene, cam, {w, h}, accelName);
  const RenderContext ctx = prepared.context(settings);
  auto integrator = makeIntegrator(ctx);
  Film film(w, h);
  renderImage(*integrator, film);
  return film;
}

/// Drops every texture: accelerator comparisons are about geometry.
void withoutTextures(Scene& scene) {
  scene.textures.clear();
  for (Material& m : scene.materials)
    m.baseColorTexture = m.metallicRoughnessTexture = m.emissiveTexture = m.normalTexture = {};
}

TEST(BvhRender, WhittedImagesMatchEmbreeOnEveryScene) {
  auto files = sceneFiles();
  ASSERT_GE(files.size(), 20u);
  double worstRmse = 0, worstPixel = 0;
  int lit = 0;
  for (const auto& file : files) {
    Scene scene = withHeadlight(loadGltf(file));
    // The accelerators' hit points differ in the last bits; textures would magnify that at
    // texel edges (up to 0.04 on LightsPunctualLamp), and this test is about geometry.
    withoutTextures(scene);
    RenderSettings s;
    s.set("integrator", "whitted");
    Film ref = render(scene, "embree", s, 96, 72);
    for (const char* accel : {"bvh", "bvh-gs"}) {
      test::FilmDifference d = test::filmDifference(render(scene, accel, s, 96, 72), ref);
      EXPECT_LE(d.rmse, 1e-5) << file << " " << accel;
      EXPECT_LE(d.maxAbs, 1e-3) << file << " " << accel;
      worstRmse = std::max(worstRmse, d.rmse);
      worstPixel = std::max(worstPixel, d.maxAbs);
      lit += d.meanB > 1e-3;
    }
  }
  std::printf("%zu scenes: worst RMSE %.3g, worst pixel difference %.3g\n", files.size(), worstRmse,
              worstPixel);
  std::printf("%d of %zu renders not black\n", lit, 2 * files.size());
  EXPECT_GE(lit, int(files.size()));  // the comparison is not between black images
}

TEST(BvhRender, PathImagesMatchEmbreeInMean) {
  auto files = sceneFiles();
  ASSERT_GE(files.size(), 20u);
  double worst = 0;
  for (const auto& file : files) {
    Scene scene = loadGltf(file);
    withoutTextures(scene);  // geometry only, as above (and MIP levels would dominate the time)
    RenderSettings s;
    s.set("integrator", "path");
    s.set("spp", 4);
    s.set("seed", 7);
    test::FilmDifference d =
        test::filmDifference(render(scene, "bvh", s, 48, 36), render(scene, "embree", s, 48, 36));
    EXPECT_LE(std::fabs(d.meanA - d.meanB), 1e-3 * std::max(d.meanB, 1e-6)) << file;
    worst = std::max(worst, std::fabs(d.meanA - d.meanB) / std::max(d.meanB, 1e-6));
  }
  std::printf("%zu scenes: worst relative difference of the mean %.3g\n", files.size(), worst);
}

}  // namespace
}  // namespace tray

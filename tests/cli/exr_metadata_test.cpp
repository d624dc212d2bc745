// EXR metadata of tray-render read back with OIIO: worldToCamera and worldToNDC (checked by
// projecting the position AOV of known pixels), render settings, version and colorspace.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/cli/cli_run.h"

namespace tray::test {
namespace {

/// p * M (Imath's row-vector convention), divided by w.
void project(const float* m, const float p[3], float out[3], float* w = nullptr) {
  float r[4];
  for (int j = 0; j < 4; ++j)
    r[j] = p[0] * m[0 * 4 + j] + p[1] * m[1 * 4 + j] + p[2] * m[2 * 4 + j] + m[12 + j];
  for (int j = 0; j < 3; ++j) out[j] = r[j] / r[3];
  if (w) *w = r[3];
}

const float* matrix(const Exr& e, const char* name) {
  const OIIO::ParamValue* p = e.spec.find_attribute(name);
  EXPECT_TRUE(p) << name;
  if (!p) return nullptr;
  EXPECT_EQ(p->type(), OIIO::TypeMatrix44) << name;
  return static_cast<const float*>(p->data());
}

/// Renders `extra` with position and depth AOVs through pixel centres and checks the camera
/// matrices against what each pixel saw.
void checkCameraMatrices(const std::string& extra, int x0, int y0) {
  const fs::path dir = testDir();
  const std::string scene = std::string(TRAY_SOURCE_DIR) + "/scenes/whitted.gltf";
  CliResult r = runCli(
      TRAY_RENDER_BIN,
      "'" + scene + "' --resolution 64x48 --pixel-sampler center --aov position,depth --float " +
          extra + " -o '" + (dir / "m.exr").string() + "'",
      dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr e = readExrFile(dir / "m.exr");
  const float* toCamera = matrix(e, "worldToCamera");
  const float* toNdc = matrix(e, "worldToNDC");
  ASSERT_TRUE(toCamera && toNdc);
  int checked = 0;
  for (int y = 0; y < e.spec.height; y += 3)
    for (int x = 0; x < e.spec.width; x += 3) {
      const float depth = e.at(x, y, "Z");
      if (!std::isfinite(depth)) continue;  // background
      const float p[3] = {e.at(x, y, "P.X"), e.at(x, y, "P.Y"), e.at(x, y, "P.Z")};
      float ndc[3], cam[3], w;
      project(toNdc, p, ndc);
      // NDC (0,0)-(1,1) spans the display window; the pixel centre of image pixel (x0+x, y0+y).
      EXPECT_NEAR(ndc[0], (x0 + x + 0.5f) / 64.0f, 2e-4f) << x << "," << y;
      EXPECT_NEAR(ndc[1], (y0 + y + 0.5f) / 48.0f, 2e-4f) << x << "," << y;
      project(toCamera, p, cam, &w);
      EXPECT_FLOAT_EQ(w, 1.0f);
      // Left-handed camera space, +z forward: the hit is at distance `depth` in front.
      EXPECT_GT(cam[2], 0.0f);
      EXPECT_NEAR(std::sqrt(cam[0] * cam[0] + cam[1] * cam[1] + cam[2] * cam[2]), depth,
                  1e-3f * depth);
      EXPECT_EQ(cam[0] > 0, x0 + x + 0.5f > 32.0f);  // +x right, +y up
      EXPECT_EQ(cam[1] > 0, y0 + y + 0.5f < 24.0f);
      ++checked;
    }
  EXPECT_GT(checked, 50);
}

TEST(ExrMetadata, CameraMatricesProjectWhatEachPixelSaw) {
  checkCameraMatrices("", 0, 0);
}

TEST(ExrMetadata, CameraMatricesOfARegionAreThoseOfTheFullImage) {
  checkCameraMatrices("--region 20,10,60,40", 20, 10);
}

TEST(ExrMetadata, RenderSettingsVersionAndColorspace) {
  const fs::path dir = testDir();
  const std::string scene = std::string(TRAY_SOURCE_DIR) + "/scenes/whitted.gltf";
  CliResult r = runCli(TRAY_RENDER_BIN,
                       "'" + scene + "' --resolution 16x12 --integrator path --spp 3 --seed 42 " +
                           "--output-colorspace ACEScg -o '" + (dir / "m.exr").string() + "'",
                       dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr e = readExrFile(dir / "m.exr");
  EXPECT_EQ(e.spec.get_string_attribute("tray:integrator"), "path");
  EXPECT_EQ(e.spec.get_float_attribute("tray:spp"), 3.0f);
  EXPECT_EQ(e.spec.get_string_attribute("tray:seed"), "42");
  // Every pixel-affecting option of the path integrator, defaults included
  // (docs/options-design.md); --debug-nan only prints, so it is not there.
  EXPECT_EQ(e.spec.get_string_attribute("tray:maxDepth"), "8");
  EXPECT_EQ(e.spec.get_string_attribute("tray:clampIndirect"), "0");
  EXPECT_EQ(e.spec.get_string_attribute("tray:pixelSampler"), "auto");
  EXPECT_FALSE(e.spec.find_attribute("tray:debugNan"));
  EXPECT_EQ(e.spec.get_string_attribute("tray:version"), TRAY_VERSION);
  EXPECT_EQ(e.spec.get_string_attribute("tray:status"), "complete");
  EXPECT_GT(e.spec.get_float_attribute("tray:renderSeconds"), 0.0f);
  EXPECT_EQ(e.spec.get_string_attribute("colorspace"), "ACEScg");
  EXPECT_TRUE(e.spec.find_attribute("chromaticities"));
  // A complete full render carries no state layer.
  EXPECT_EQ(e.channel("tray.done"), -1);
}

// tray:renderCpuSeconds is the render's CPU time alone (benchmarks compare it across
// renderers): on one thread it cannot exceed the render's wall time, which it would if it
// counted from the process's start (scene loading, Embree's build, OCIO's set-up), or if
// another thread spun meanwhile: OpenBLAS's, which tray-render stops (io/library_threads.h).
// Without that, this render's CPU time was twice its wall time. The tests' environment gives
// OpenBLAS no thread (tests/CMakeLists.txt): this one runs tray-render without it.
TEST(ExrMetadata, RenderCpuSecondsCountTheRenderAlone) {
  const fs::path dir = testDir();
  const std::string scene = std::string(TRAY_SOURCE_DIR) + "/scenes/whitted.gltf";
  std::string args = "-u OPENBLAS_NUM_THREADS '";
  args += TRAY_RENDER_BIN;
  args += "' '" + scene + "' --resolution 48x36 --integrator path --spp 64 --threads 1 -q -o '" +
          (dir / "t.exr").string() + "'";
  CliResult r = runTool("/usr/bin/env", args, dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr e = readExrFile(dir / "t.exr");
  const float wall = e.spec.get_float_attribute("tray:renderSeconds");
  const float cpu = e.spec.get_float_attribute("tray:renderCpuSeconds");
  EXPECT_GT(cpu, 0.0f);
  EXPECT_LE(cpu, wall * 1.05f + 0.01f) << "wall " << wall;
}

}  // namespace
}  // namespace tray::test

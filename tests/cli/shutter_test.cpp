// --shutter and --motion-steps through the real tray-render: bad values refused before
// rendering with one line and exit 2, the blur showing on an animated file, a file with
// nothing moving rendering the same bits, and both options in the EXR metadata.
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/cli/cli_run.h"

namespace tray {
namespace {

using namespace tray::test;

const std::string kBox = std::string(TRAY_SHARED_DIR) + "/gltf-features/BoxAnimated.glb";
const std::string kCornell = std::string(TRAY_SHARED_DIR) + "/reference/cornell-box.gltf";

/// One line on stderr holding `text`, and nothing written.
void expectRefused(const CliResult& r, const std::string& text, const fs::path& out) {
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Shutter, BadValuesFailBeforeRendering) {
  const fs::path dir = testDir();
  const fs::path out = dir / "a.exr";
  const std::string run =
      quoted(fs::path(kBox)) + " --resolution 8x6 --time 1 -o " + quoted(out) + " ";
  expectRefused(runCli(TRAY_RENDER_BIN, run + "--shutter 0.5,0.25", dir),
                "--shutter 0.5,0.25: the shutter must close after it opens", out);
  expectRefused(runCli(TRAY_RENDER_BIN, run + "--shutter 0.25,0.25", dir),
                "must close after it opens", out);
  expectRefused(runCli(TRAY_RENDER_BIN, run + "--shutter 0.5", dir),
                "--shutter 0.5: expected OPEN,CLOSE", out);
  expectRefused(runCli(TRAY_RENDER_BIN, run + "--shutter a,b", dir), "expected OPEN,CLOSE", out);
  expectRefused(runCli(TRAY_RENDER_BIN, run + "--shutter 0,inf", dir), "expected OPEN,CLOSE", out);
  expectRefused(runCli(TRAY_RENDER_BIN, run + "--shutter 0,0.5 --motion-steps 1", dir),
                "motion-steps", out);
  // No animation time: the static pose has nothing to open the shutter around.
  const std::string still = quoted(fs::path(kBox)) + " --resolution 8x6 -o " + quoted(out) + " ";
  expectRefused(runCli(TRAY_RENDER_BIN, still + "--shutter -0.25,0.25", dir),
                "--shutter needs an animation time", out);
}

TEST(Shutter, BlursWhatMovesAndKeepsEveryBitWhereNothingDoes) {
  const fs::path dir = testDir();
  const std::string box =
      quoted(fs::path(kBox)) + " --resolution 32x24 --spp 4 --threads 2 --time 1 ";
  CliResult r = runCli(TRAY_RENDER_BIN, box + "-o " + quoted(dir / "sharp.exr"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runCli(TRAY_RENDER_BIN,
             box + "--fps 1 --shutter -0.5,0.5 --motion-steps 5 -o " + quoted(dir / "blur.exr"),
             dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr blur = readExrFile(dir / "blur.exr");
  EXPECT_NE(blur.pixels, readExrFile(dir / "sharp.exr").pixels);
  EXPECT_EQ(blur.spec.get_string_attribute("tray:shutter"), "-0.5,0.5");
  EXPECT_EQ(blur.spec.get_string_attribute("tray:motionSteps"), "5");

  // A scene without animations: a shutter changes nothing, bit for bit.
  const std::string cornell =
      quoted(fs::path(kCornell)) + " --integrator path --resolution 24x24 --spp 4 --time 0 ";
  r = runCli(TRAY_RENDER_BIN, cornell + "-o " + quoted(dir / "c.exr"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runCli(TRAY_RENDER_BIN, cornell + "--shutter -0.25,0.25 -o " + quoted(dir / "cs.exr"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(readExrFile(dir / "c.exr").pixels, readExrFile(dir / "cs.exr").pixels);
}

// --aov motion: Nuke's motion.u / motion.v, non-zero on the moving box, zero on its static
// base (the camera does not move).
TEST(Shutter, MotionVectorLayerShowsWhatMoves) {
  const fs::path dir = testDir();
  const std::string box =
      quoted(fs::path(kBox)) + " --resolution 32x24 --time 1 --aov motion,objectid --float ";
  CliResult r = runCli(TRAY_RENDER_BIN, box + "-o " + quoted(dir / "v.exr"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr v = readExrFile(dir / "v.exr");
  ASSERT_GE(v.channel("motion.u"), 0);
  ASSERT_GE(v.channel("motion.v"), 0);
  int moving = 0, still = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) {
      const float u = v.at(x, y, "motion.u"), w = v.at(x, y, "motion.v");
      if (v.at(x, y, "objectid.id") < 0) continue;
      (u != 0 || w != 0 ? moving : still) += 1;
    }
  EXPECT_GT(moving, 10);
  EXPECT_GT(still, 10);
}

}  // namespace
}  // namespace tray

// --frames and --time through the real tray-render: frame patterns in -o, one image per frame,
// frames that differ, and the same time rendering the same pixels; the pattern helpers alone.
#include "cli/frames.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "tests/cli/cli_run.h"

namespace tray {
namespace {

using namespace tray::test;

TEST(FramePattern, HashesAndPrintfAreZeroPadded) {
  EXPECT_EQ(framePath("out.####.exr", 7), "out.0007.exr");
  EXPECT_EQ(framePath("out.##.png", 123), "out.123.png");
  EXPECT_EQ(framePath("f/%04d.exr", 42), "f/0042.exr");
  EXPECT_EQ(framePath("f/%d.exr", 42), "f/42.exr");
  EXPECT_FALSE(hasFramePattern("out.exr"));
  EXPECT_TRUE(hasFramePattern("out.#.exr"));
}

TEST(FramePattern, RangesAndOutputsAreChecked) {
  EXPECT_EQ(parseFrameRange("3-10").first, 3);
  EXPECT_EQ(parseFrameRange("3-10").last, 10);
  EXPECT_EQ(parseFrameRange("5").last, 5);
  EXPECT_THROW(parseFrameRange("10-3"), Error);
  EXPECT_THROW(parseFrameRange("-3"), Error);
  EXPECT_THROW(parseFrameRange("a-b"), Error);
  EXPECT_THROW(checkFramePatterns({"out.####.exr", "out.png"}, true), Error);
  EXPECT_THROW(checkFramePatterns({"out.####.exr"}, false), Error);
  EXPECT_NO_THROW(checkFramePatterns({"out.####.exr", "p.%04d.png"}, true));
}

const std::string kBox = std::string(TRAY_SHARED_DIR) + "/gltf-features/BoxAnimated.glb";

std::vector<float> pixels(const fs::path& file) { return readExrFile(file).pixels; }

TEST(Frames, TwoFramesDifferAndTheSameTimeRendersTheSamePixels) {
  const fs::path dir = testDir();
  // fps 0.5: frame 0 at t = 0, frame 1 at t = 2 (the box risen and turned).
  const std::string common = "'" + kBox + "' --resolution 24x18 ";
  CliResult r = runCli(TRAY_RENDER_BIN,
                       common + "--threads 2 --frames 0-1 --fps 0.5 -o '" + (dir / "out.####.exr").string() + "'",
                       dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir / "out.0000.exr"));
  ASSERT_TRUE(fs::exists(dir / "out.0001.exr"));
  EXPECT_NE(pixels(dir / "out.0000.exr"), pixels(dir / "out.0001.exr"));
  // The unlit asset's warning is said once, not once per frame.
  const std::string unlit = "has no lights of meaningful power";
  const size_t first = r.err.find(unlit);
  EXPECT_NE(first, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(unlit, first + 1), std::string::npos) << r.err;
  EXPECT_EQ(readExrFile(dir / "out.0001.exr").spec.get_string_attribute("tray:time"), "2");
  // --time 2 alone, with another thread count: the pixels of frame 1.
  r = runCli(TRAY_RENDER_BIN, common + "--time 2 --threads 1 -o '" + (dir / "t2.exr").string() + "'",
             dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(pixels(dir / "t2.exr"), pixels(dir / "out.0001.exr"));
}

TEST(Frames, BadRequestsFailBeforeRendering) {
  const fs::path dir = testDir();
  const std::string box = "'" + kBox + "' --resolution 8x6 ";
  CliResult r = runCli(TRAY_RENDER_BIN, box + "--frames 0-1 -o '" + (dir / "one.exr").string() + "'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("needs a frame pattern"), std::string::npos) << r.err;
  r = runCli(TRAY_RENDER_BIN, box + "--time soon -o '" + (dir / "a.exr").string() + "'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--time soon: expected seconds"), std::string::npos) << r.err;
  r = runCli(TRAY_RENDER_BIN, box + "--time 1 --frames 0-1 -o '" + (dir / "a.####.exr").string() + "'", dir);
  EXPECT_EQ(r.exitCode, 2);
  r = runCli(TRAY_RENDER_BIN, box + "--time 1 --animation 4 -o '" + (dir / "a.exr").string() + "'", dir);
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--animation 4: no such animation (the file has 1: 0; or first, all)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "a.exr"));
}

}  // namespace
}  // namespace tray

// Noise-driven adaptive sampling and time limits end to end through tray-render and tray-merge
// (docs/adaptive-sampling.md): regions and sample ranges merge, a real SIGINT resumes bit for
// bit, mistakes are one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "tests/cli/cli_run.h"

namespace tray::test {
namespace {

const std::string kCornell = std::string(TRAY_SHARED_DIR) + "/reference/cornell-box.gltf";
const std::string kJob = "'" + kCornell +
                         "' --integrator path --noise-threshold 0.05 --aov depth,normal,albedo,"
                         "samples --seed 3 ";

std::string out(const fs::path& dir, const std::string& name) {
  return "-o '" + (dir / name).string() + "'";
}

/// The samples layer's smallest and largest count.
std::pair<float, float> countRange(const Exr& image) {
  float lo = 1e30f, hi = 0;
  for (int y = 0; y < image.spec.height; ++y)
    for (int x = 0; x < image.spec.width; ++x) {
      const float n = image.at(x, y, "samples.count");
      lo = std::min(lo, n), hi = std::max(hi, n);
    }
  return {lo, hi};
}

// Bands whose edges are multiples of 8 (tray-farm's) decide as the whole image: the merge is
// the full render bit for bit, and samples went where the noise is.
TEST(NoiseThreshold, RegionsMergeBitForBit) {
  const fs::path dir = testDir();
  const std::string job = kJob + "--spp 64 --resolution 40x32";
  expectRegionsMergeToWhole(job, {"0,0,40,8", "0,8,40,32"}, dir, "noise-threshold regions");
  const Exr full = readExrFile(dir / "full.exr");
  const auto [lo, hi] = countRange(full);
  EXPECT_EQ(lo, 16.0f);
  EXPECT_EQ(hi, 64.0f);
  EXPECT_GT(full.spec.get_float_attribute("tray:samplesDone"), 16.0f * 40 * 32);
  EXPECT_LT(full.spec.get_float_attribute("tray:samplesDone"), 64.0f * 40 * 32);
}

// Sample-range parts each spend their own range adaptively; the merge adds their sums and
// counts (the rule: the threshold applies to each part's samples).
TEST(NoiseThreshold, SampleRangePartsMergeTheirCounts) {
  const fs::path dir = testDir();
  const std::string job = kJob + "--spp 64 --resolution 24x16";
  float samples = 0;
  std::string parts;
  for (const char* range : {"0,32", "32,64"}) {
    const std::string name = std::string(range) + ".exr";
    CliResult r =
        runCli(TRAY_RENDER_BIN, job + " --sample-range " + range + " " + out(dir, name), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    samples += readExrFile(dir / name).spec.get_float_attribute("tray:samplesDone");
    parts += " '" + (dir / name).string() + "'";
  }
  CliResult m = runMerge(parts + " " + out(dir, "merged.exr"), dir);
  ASSERT_EQ(m.exitCode, 0) << m.err;
  const Exr merged = readExrFile(dir / "merged.exr");
  EXPECT_EQ(merged.spec.get_float_attribute("tray:samplesDone"), samples);
  EXPECT_LT(samples, 64.0f * 24 * 16);
}

// A real SIGINT mid-render: the partial EXR keeps the progress (layer tray_progress), and
// --resume finishes it to the uninterrupted render's pixels.
TEST(NoiseThreshold, InterruptedRenderResumesBitForBit) {
  const fs::path dir = testDir();
  const std::string job = kJob + "--spp 256 --resolution 101x93";
  ASSERT_EQ(runCli(TRAY_RENDER_BIN, job + " " + out(dir, "full.exr"), dir).exitCode, 0);
  CliResult r = interruptCli(job + " " + out(dir, "part.exr"));
  ASSERT_EQ(r.exitCode, 130) << r.err;
  const Exr partial = readExrFile(dir / "part.exr");
  EXPECT_EQ(partial.spec.get_string_attribute("tray:status"), "partial");
  const auto& names = partial.spec.channelnames;
  EXPECT_NE(std::find(names.begin(), names.end(), "tray_progress.count"), names.end());
  r = runCli(TRAY_RENDER_BIN, job + " --resume " + out(dir, "part.exr"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr resumed = readExrFile(dir / "part.exr");
  EXPECT_EQ(resumed.spec.get_string_attribute("tray:status"), "complete");
  expectSamePixels(readExrFile(dir / "full.exr"), resumed, "resumed");
}

// --time-limit ends a render that would take hours, complete and said so.
TEST(NoiseThreshold, TimeLimitEndsTheRender) {
  const fs::path dir = testDir();
  CliResult r = runTool(TRAY_RENDER_BIN,
                        "'" + kCornell +
                            "' --integrator path --spp 1000000 --time-limit 1 --resolution "
                            "32x32 --aov samples " +
                            out(dir, "t.exr"),
                        dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr image = readExrFile(dir / "t.exr");
  EXPECT_EQ(image.spec.get_string_attribute("tray:status"), "complete");
  const auto [lo, hi] = countRange(image);
  EXPECT_GE(lo, 16.0f);
  EXPECT_LT(hi, 1000000.0f);
}

// Mistakes: one line, exit 2, nothing written.
TEST(NoiseThreshold, MistakesAreOneLine) {
  const fs::path dir = testDir();
  const std::string job = "'" + kCornell + "' --resolution 16x16 --spp 8 ";
  for (const std::string bad :
       {"--noise-threshold -1", "--noise-threshold nan", "--min-spp 0", "--time-limit -2",
        "--time-limit inf", "--integrator adaptive --noise-threshold 0.1",
        "--integrator path --noise-threshold 0.1 --aov lightpaths",
        "--integrator path --time-limit 5 --pixel-sampler jitter"}) {
    CliResult r = runCli(TRAY_RENDER_BIN, job + bad + " " + out(dir, "x.exr"), dir);
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

}  // namespace
}  // namespace tray::test

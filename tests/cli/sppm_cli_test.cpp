// tray-render --integrator sppm through the real binaries (docs/sppm.md): farm bands rendered
// with --region and merged by tray-merge equal one full render bit for bit, AOVs and
// Cryptomatte included; a sample range is refused with one line.
#include <gtest/gtest.h>

#include "tests/cli/cli_run.h"

namespace tray::test {
namespace {

const std::string kPlainJob = "'" + std::string(TRAY_SHARED_DIR) +
                              "/reference/cornell-box.gltf' --integrator sppm --spp 3 --photons "
                              "20000 --seed 3 --resolution 31x23";
const std::string kJob = kPlainJob + " --aov all";

std::string out(const fs::path& dir, const std::string& name) {
  return "-o '" + (dir / name).string() + "'";
}

TEST(SppmCli, BandsMergeBitForBit) {
  const fs::path dir = testDir();
  ASSERT_EQ(runCli(TRAY_RENDER_BIN, kJob + " " + out(dir, "full.exr"), dir).exitCode, 0);
  const char* bands[] = {"0,0,31,9", "0,9,31,10", "0,10,31,23"};
  std::string parts;
  for (int i = 0; i < 3; ++i) {
    const std::string name = std::string("b") + char('0' + i) + ".exr";
    const CliResult r =
        runCli(TRAY_RENDER_BIN, kJob + " --region " + bands[i] + " " + out(dir, name), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    parts += " '" + (dir / name).string() + "'";
  }
  const CliResult m = runMerge(parts + " " + out(dir, "merged.exr"), dir);
  ASSERT_EQ(m.exitCode, 0) << m.err;
  expectSamePixels(readExrFile(dir / "full.exr"), readExrFile(dir / "merged.exr"), "3 bands");
}

TEST(SppmCli, SampleRangesAreRefusedWithOneLine) {
  const fs::path dir = testDir();
  const CliResult r =
      runCli(TRAY_RENDER_BIN, kPlainJob + " --sample-range 0,2 " + out(dir, "part.exr"), dir);
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("--sample-range: sppm renders whole frames"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--region"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tray::test

// tray-render's own checks at the boundary: option values it must refuse, the out-of-memory
// message, the half-float overflow warning, and one pixel sample of the white furnace that once
// came back black.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "tests/cli/cli_run.h"

namespace tray::test {
namespace {

const std::string kScene = quoted(fs::path(TRAY_SOURCE_DIR) / "scenes" / "whitted.gltf");

size_t lines(const std::string& s) {
  return size_t(std::count(s.begin(), s.end(), '\n'));
}

TEST(CliOptions, NegativeSeedCameraOrSceneIsAnErrorNotADefault) {
  const fs::path dir = testDir();
  for (const std::string option : {"--seed", "--camera", "--scene"}) {
    for (const std::string value : {"-1", "-7"}) {
      const fs::path out = dir / "x.exr";
      CliResult r = runCli(TRAY_RENDER_BIN,
                           kScene + " --resolution 8x6 " + option + " " + value + " -o " +
                               quoted(out),
                           dir);
      EXPECT_EQ(r.exitCode, 2) << option << " " << value << ": " << r.err;
      EXPECT_EQ(lines(r.err), 1u) << r.err;
      EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
      // "negative" (--camera/--scene) or the option table's range (--seed: ">= 0").
      EXPECT_TRUE(r.err.find("negative") != std::string::npos ||
                  r.err.find(">= 0") != std::string::npos)
          << r.err;
      EXPECT_FALSE(fs::exists(out)) << option << " " << value;
    }
  }
  // Explicit 0 is fine, and so is the largest seed, 2^63 - 1 (the option table's integers).
  CliResult ok = runCli(TRAY_RENDER_BIN,
                        kScene + " --resolution 8x6 --camera 0 --scene 0 --seed " +
                            "9223372036854775807 -o " + quoted(dir / "ok.exr"),
                        dir);
  EXPECT_EQ(ok.exitCode, 0) << ok.err;
}

// Issue 40: NaN passed every range check of the options declared in the CLI (each comparison
// with it is false), --resolution's %d wrapped 4294967360 to 64, and an empty --env or
// --animation was taken for the default. Each is now one line and exit 2, with nothing written.
TEST(CliOptions, NanHugeAndEmptyValuesAreRefused) {
  const fs::path dir = testDir();
  const fs::path out = dir / "x.png";
  for (const std::string bad :
       {"--max-memory nan", "--max-memory -nan", "--texture-memory NaN", "--checkpoint nan",
        "--progress-step nan", "--progress-seconds inf", "--max-memory 1e999",
        "--resolution 4294967360x48", "--resolution 64x4294967344", "--resolution ''",
        "--resolution 64x48x", "--resolution +64x48", "--resolution ' 64x48'", "--env ''",
        "--animation ''", "--max-depth ''"}) {
    CliResult r =
        runCli(TRAY_RENDER_BIN, kScene + " --resolution 8x6 " + bad + " -o " + quoted(out), dir);
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1u) << bad << ": " << r.err;
    const std::string option = bad.substr(0, bad.find(' '));
    EXPECT_NE(r.err.find(option), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
  // The edges still pass.
  CliResult ok = runCli(TRAY_RENDER_BIN,
                        kScene + " --resolution 16x1 --max-memory 0 --progress-step 100 " +
                            "--progress-seconds 0 -o " + quoted(dir / "ok.png"),
                        dir);
  EXPECT_EQ(ok.exitCode, 0) << ok.err;
}

// Issue 40: an emitter near float's maximum made samples overflow, and they were dropped
// without a word under -q (the summary line, which -q hides, lumped them with NaN). Now one
// warning line says how many, and that they were infinite, whatever the verbosity.
TEST(CliOptions, OverflowingSamplesAreSaidEvenWhenQuiet) {
  const fs::path dir = testDir();
  std::ifstream in(fs::path(TRAY_SHARED_DIR) / "reference" / "cornell-box.gltf");
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const size_t at = text.find("18.387");  // the light's emissiveStrength
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 6, "3.4e38");
  std::ofstream(dir / "hot.gltf") << text;
  CliResult r = runCli(TRAY_RENDER_BIN,
                       quoted(dir / "hot.gltf") + " --integrator path --spp 4 --resolution 32x32 "
                                                  "-q -o " + quoted(dir / "hot.png"),
                       dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("not finite were discarded"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("infinite: radiance beyond float's range"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(" 0 infinite"), std::string::npos) << r.err;  // counted as infinite
  // An ordinary scene says nothing of the kind.
  CliResult calm = runCli(TRAY_RENDER_BIN, kScene + " --resolution 8x6 -q -o " +
                                               quoted(dir / "calm.png"),
                          dir);
  EXPECT_EQ(calm.exitCode, 0);
  EXPECT_EQ(calm.err.find("not finite"), std::string::npos) << calm.err;
}

// CLI11 2.1 parsed `--debug-nan=xyz` with std::stoll and the exception escaped: tray-render
// died with "terminate called" (found by fuzz/options_fuzz). Every declared flag now refuses a
// value it does not understand in one line, and still takes the spellings CLI11 documents.
TEST(CliOptions, AFlagWithAnUnknownValueIsOneLineNotACrash) {
  const fs::path dir = testDir();
  for (const std::string flag : {"--debug-nan", "--transparent", "--aa-robust"}) {
    const fs::path out = dir / "flag.exr";
    CliResult r = runCli(TRAY_RENDER_BIN,
                         kScene + " --resolution 8x6 " + flag + "=xyz -o " + quoted(out), dir);
    EXPECT_EQ(r.exitCode, 2) << flag << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(flag), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("'xyz'"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << flag;
  }
  for (const std::string value : {"true", "false", "on", "0"}) {
    CliResult ok = runCli(TRAY_RENDER_BIN,
                          kScene + " --resolution 8x6 --transparent=" + value + " -o " +
                              quoted(dir / "ok.exr"),
                          dir);
    EXPECT_EQ(ok.exitCode, 0) << value << ": " << ok.err;
  }
}

TEST(CliOptions, AnOptionTheIntegratorDoesNotReadIsSaidNotSilentlyIgnored) {
  // A farm may pass one set of options to every integrator: a warning, not an error. Before,
  // --clamp-indirect or --rr-depth with whitted rendered without a word.
  const fs::path dir = testDir();
  struct Case {
    std::string args, warning;  // warning: "" for none
  } cases[] = {
      {"--integrator whitted --clamp-indirect 3",
       "warning: --clamp-indirect has no effect with --integrator whitted (an option of path, "
       "path-scalar, path-wavefront)\n"},
      {"--integrator adaptive --rr-depth 3",
       "warning: --rr-depth has no effect with --integrator adaptive --inner whitted (an option "
       "of path, path-scalar, path-wavefront)\n"},
      {"--integrator path --rr-depth 3 --max-depth 4", ""},
      {"--integrator adaptive --inner path --rr-depth 3", ""},
      {"--integrator whitted --max-depth 3 --spp 2", ""},  // whitted's own --max-depth
  };
  for (const Case& c : cases) {
    CliResult r = runCli(TRAY_RENDER_BIN,
                         kScene + " -q --resolution 8x6 " + c.args + " -o " +
                             quoted(dir / "unread.exr"),
                         dir);
    EXPECT_EQ(r.exitCode, 0) << c.args << ": " << r.err;
    EXPECT_EQ(r.err, c.warning) << c.args;
  }
}

TEST(CliOptions, RequiredExtensionExits2UnlessIgnored) {
  const fs::path dir = testDir();
  const fs::path scene = dir / "required.gltf";
  std::ofstream(scene) << R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_magic"],
      "extensionsRequired":["EXT_magic"],"scenes":[{"nodes":[]}]})";
  const std::string args = quoted(scene) + " --resolution 8x6 -o " + quoted(dir / "x.exr");
  CliResult refused = runCli(TRAY_RENDER_BIN, args, dir);
  EXPECT_EQ(refused.exitCode, 2) << refused.err;
  EXPECT_NE(refused.err.find("required extension 'EXT_magic' is not supported"),
            std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
  CliResult anyway = runCli(TRAY_RENDER_BIN, args + " --ignore-required-extensions", dir);
  EXPECT_EQ(anyway.exitCode, 0) << anyway.err;
  EXPECT_NE(anyway.err.find("warning: " + scene.string() + ": required extension 'EXT_magic'"),
            std::string::npos) << anyway.err;
  EXPECT_TRUE(fs::exists(dir / "x.exr"));
}

TEST(CliOutOfMemory, ReportsThePhaseAndExits1) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ASan reserves terabytes of address space: no address-space limit applies";
#endif
  const fs::path dir = testDir();
  if (std::system("prlimit --as=1000000000 true >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "prlimit cannot limit the address space here";
  // 16384 x 16384 pixels of RGBA float are 4 GiB: more than the 3 GB address space allowed,
  // while loading the scene and building the accelerator take under 1 GB (two malloc arenas:
  // glibc reserves 64 MiB of address space for each, up to 8 per core).
  CliResult r = runTool("env",
                        "MALLOC_ARENA_MAX=2 prlimit --as=3000000000 " + quoted(TRAY_RENDER_BIN) +
                            " " + kScene +
                            " -q --threads 1 --resolution 16384x16384 -o " +
                            quoted(dir / "big.exr"),
                        dir);
  EXPECT_EQ(r.exitCode, 1) << r.err;
  EXPECT_EQ(lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("tray-render: error: out of memory while rendering"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "big.exr"));
}

TEST(CliHalfOverflow, ClampsTo65504AndWarnsOnce) {
  const fs::path dir = testDir();
  // Nothing but a sphere in an environment of radiance 1e6, beyond half's 65504.
  const fs::path scene = dir / "bright.gltf";
  std::ofstream(scene) << R"({"asset": {"version": "2.0"}, "scene": 0,
    "extensionsUsed": ["TRAY_shape", "TRAY_environment"],
    "scenes": [{"nodes": [0], "extensions": {"TRAY_environment": {"background": [1e6, 1e6, 1e6]}}}],
    "nodes": [{"extensions": {"TRAY_shape": {"type": "sphere", "radius": 1}},
               "translation": [0, 0, -5]}]})";
  CliResult half = runCli(TRAY_RENDER_BIN,
                          quoted(scene) + " --resolution 8x6 -o " + quoted(dir / "half.exr"),
                          dir);
  ASSERT_EQ(half.exitCode, 0) << half.err;
  EXPECT_EQ(lines(half.err), 1u) << half.err;
  EXPECT_NE(half.err.find("half.exr: "), std::string::npos) << half.err;
  EXPECT_NE(half.err.find("clamped to +-65504 (use --float"), std::string::npos) << half.err;
  const Exr e = readExrFile(dir / "half.exr");
  EXPECT_EQ(e.spec.channelformat(0), OIIO::TypeDesc::HALF);
  EXPECT_EQ(e.at(0, 0, "R"), 65504.0f);  // a corner sees the environment: finite, not +Inf

  CliResult full = runCli(TRAY_RENDER_BIN,
                          quoted(scene) + " --resolution 8x6 --float -o " +
                              quoted(dir / "float.exr"),
                          dir);
  ASSERT_EQ(full.exitCode, 0) << full.err;
  EXPECT_EQ(full.err, "");
  EXPECT_EQ(readExrFile(dir / "float.exr").at(0, 0, "R"), 1e6f);
}

TEST(CliFurnace, TheLostSampleIsNotBlack) {
  // Issue 18: seed 0, 256 x 256, pixel (48, 111), sample 168 of 256 (Sobol'): the diffuse
  // bounce off the albedo-0.8 sphere drew u = 0, sampleCosineHemisphere returned a direction on
  // the horizon with pdf 0, the path ended there, and the sample was exactly 0. Inside the
  // emissive enclosure the BSDF sample is the only estimator (no light samples from inside a
  // sphere light), so it must give 0.8 x 1.
  const fs::path dir = testDir();
  const fs::path scene = fs::path(TRAY_SHARED_DIR) / "reference" / "furnace-sphere.gltf";
  if (!fs::exists(scene)) GTEST_SKIP() << scene << " is missing";
  CliResult r = runCli(TRAY_RENDER_BIN,
                       quoted(scene) + " --resolution 256x256 --integrator path --spp 256 " +
                           "--sampler sobol --seed 0 --region 48,111,49,112 --sample-range " +
                           "168,169 --float -o " + quoted(dir / "f.exr"),
                       dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr e = readExrFile(dir / "f.exr");
  ASSERT_EQ(e.spec.width, 1);
  for (const char* c : {"R", "G", "B"}) EXPECT_NEAR(e.at(0, 0, c), 0.8f, 1e-4f) << c;
}

TEST(CliCamera, UnknownCameraIsOneLineListingTheCameras) {
  const fs::path dir = testDir();
  for (const std::string value : {"1", "NoSuchNode"}) {
    CliResult r = runCli(TRAY_RENDER_BIN,
                         kScene + " --resolution 8x6 --camera " + value + " -o " +
                             quoted(dir / "x.exr"),
                         dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("--camera"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the scene places: 0"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "x.exr"));
  }
}

TEST(CliDefaultLight, NoDefaultLightLeavesAnUnlitAssetBlack) {
  const fs::path dir = testDir();
  const fs::path scene = fs::path(TRAY_SHARED_DIR) / "gltf-samples" / "Box.glb";
  if (!fs::exists(scene)) GTEST_SKIP() << scene << " is missing";
  const std::string args = quoted(scene) + " -q --resolution 8x6 --float -o ";
  CliResult lit = runCli(TRAY_RENDER_BIN, args + quoted(dir / "lit.exr"), dir);
  ASSERT_EQ(lit.exitCode, 0) << lit.err;
  EXPECT_NE(lit.err.find("default headlight"), std::string::npos) << lit.err;
  CliResult dark =
      runCli(TRAY_RENDER_BIN, args + quoted(dir / "dark.exr") + " --no-default-light", dir);
  ASSERT_EQ(dark.exitCode, 0) << dark.err;
  EXPECT_EQ(dark.err, "");
  const Exr a = readExrFile(dir / "lit.exr"), b = readExrFile(dir / "dark.exr");
  float litSum = 0;
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x)
      for (const char* c : {"R", "G", "B"}) {
        litSum += a.at(x, y, c);
        EXPECT_EQ(b.at(x, y, c), 0.0f) << x << "," << y;
      }
  EXPECT_GT(litSum, 1.0f);
  EXPECT_EQ(b.at(4, 3, "A"), 1.0f);  // the box is still there, unlit
}

TEST(CliDefaultLight, ASkyBoxAroundTheCameraGetsAHeadlightNotABlackImage) {
  // An unlit sphere inside a 40 m box: the default key light and environment cannot get in.
  const fs::path dir = testDir();
  const fs::path scene = dir / "skybox.gltf";
  std::ofstream(scene) << R"({"asset": {"version": "2.0"}, "extensionsUsed": ["TRAY_shape"],
    "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
    "nodes": [{"camera": 0, "translation": [0, 0, 5]},
      {"extensions": {"TRAY_shape": {"type": "sphere", "radius": 1}}},
      {"name": "sky", "extensions": {"TRAY_shape": {"type": "box", "min": [-20, -20, -20],
                                                    "max": [20, 20, 20]}}}]})";
  const std::string args = " -q --integrator=path --spp 4 --resolution 8x6 --float -o ";
  CliResult r = runCli(TRAY_RENDER_BIN, quoted(scene) + args + quoted(dir / "sky.exr"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("default headlight"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the camera is enclosed (a sky box?)"), std::string::npos) << r.err;
  EXPECT_EQ(lines(r.err), 2u) << r.err;
  const Exr image = readExrFile(dir / "sky.exr");
  EXPECT_GT(image.at(4, 3, "R"), 0.05f);  // the sphere, lit (black before the headlight)
}

}  // namespace
}  // namespace tray::test

// Environment maps from files: values read back as written (EXR and Radiance HDR), a tagged
// colorspace converted to linear Rec.709, and every bad input refused with one line naming the
// file (missing, unreadable, NaN/Inf, too large), before anything renders; a map not 2:1 warns.
#include "io/environment_map.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>

#include "core/error.h"
#include "core/render_options.h"
#include "gltf/gltf_loader.h"
#include "tests/cli/cli_run.h"

namespace tray {
namespace {

using namespace tray::test;

/// Writes a w x h RGB float image whose pixel (x, y) is (x, y, x + y) / 10, then `patch`.
std::string writeMap(const fs::path& path, int w, int h, float patch = 0.0f,
                     const std::string& colorspace = "") {
  std::vector<float> px(size_t(w) * size_t(h) * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = &px[(size_t(y) * size_t(w) + size_t(x)) * 3];
      p[0] = float(x) / 10, p[1] = float(y) / 10, p[2] = float(x + y) / 10;
    }
  if (patch != 0.0f) px[4] = patch;
  OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::FLOAT);
  if (!colorspace.empty()) spec.attribute("colorspace", colorspace);
  auto out = OIIO::ImageOutput::create(path.string());
  EXPECT_TRUE(out && out->open(path.string(), spec) &&
              out->write_image(OIIO::TypeDesc::FLOAT, px.data()) && out->close());
  return path.string();
}

/// The message of the tray::Error that loading `path` throws ("" if none).
std::string loadError(const std::string& path) {
  try {
    loadEnvironmentMap(path, nullptr);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::kInput);
    return e.what();
  }
  return "";
}

TEST(EnvironmentMap, ReadsExrAndHdrAsWritten) {
  const fs::path dir = testDir();
  for (const char* name : {"m.exr", "m.hdr"}) {
    std::vector<std::string> warnings;
    const auto map = loadEnvironmentMap(writeMap(dir / name, 16, 8), &warnings);
    ASSERT_EQ(map->width, 16);
    ASSERT_EQ(map->height, 8);
    EXPECT_TRUE(warnings.empty());
    const float* p = &map->rgb[(size_t(5) * 16 + 9) * 3];  // pixel (9, 5)
    // Radiance HDR stores an 8-bit mantissa per channel with a shared exponent.
    const float tol = std::string(name) == "m.exr" ? 0.0f : 0.01f;
    EXPECT_NEAR(p[0], 0.9f, tol) << name;
    EXPECT_NEAR(p[1], 0.5f, tol) << name;
    EXPECT_NEAR(p[2], 1.4f, 2 * tol) << name;
  }
}

TEST(EnvironmentMap, TaggedColorspaceIsConvertedToLinearRec709) {
  const fs::path dir = testDir();
  // A flat ACEScg colour: its luminance stays (both spaces share Y up to the white's
  // adaptation), its components change.
  std::vector<float> px(8 * 4 * 3);
  for (size_t i = 0; i < px.size(); i += 3) px[i] = 0.2f, px[i + 1] = 0.5f, px[i + 2] = 0.3f;
  OIIO::ImageSpec spec(8, 4, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("colorspace", "ACEScg");
  const std::string path = (dir / "acescg.exr").string();
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, px.data()) &&
              out->close());
  const auto map = loadEnvironmentMap(path, nullptr);
  const Color c(map->rgb[0], map->rgb[1], map->rgb[2]);
  const double yAp1 = 0.2722287 * 0.2 + 0.6740818 * 0.5 + 0.0536895 * 0.3;
  EXPECT_NEAR(luminance(c), yAp1, 0.01);
  EXPECT_GT(std::fabs(c.x - 0.2f), 0.02f);
  // Tagged as the working space: untouched.
  const auto same = loadEnvironmentMap(writeMap(dir / "rec709.exr", 8, 4, 0, "lin_rec709"), nullptr);
  EXPECT_EQ(same->rgb[3], 0.1f);
}

TEST(EnvironmentMap, BadFilesGiveOneLineNamingTheFile) {
  const fs::path dir = testDir();
  const std::string missing = (dir / "missing.exr").string();
  EXPECT_NE(loadError(missing).find(missing + ": environment map not found"), std::string::npos);
  const std::string garbage = (dir / "garbage.exr").string();
  std::ofstream(garbage) << "not an image\n";
  EXPECT_NE(loadError(garbage).find(garbage + ": cannot read"), std::string::npos);
  EXPECT_NE(loadError(dir.string()).find("not a regular file"), std::string::npos);
  for (float bad : {NAN, INFINITY}) {
    const std::string path = writeMap(dir / "nan.exr", 16, 8, bad);
    const std::string e = loadError(path);
    EXPECT_NE(e.find(path + ": environment map has NaN or infinite values (first at pixel 1,0)"),
              std::string::npos)
        << e;
  }
  const std::string wide = writeMap(dir / "wide.exr", kMaxEnvironmentWidth + 1, 1);
  EXPECT_NE(loadError(wide).find(wide + ": environment map of 16385x1 pixels is over the limit"),
            std::string::npos);
  for (const std::string& e : {loadError(missing), loadError(wide)})
    EXPECT_EQ(e.find('\n'), std::string::npos);
}

/// The process's peak resident memory so far, in MB.
double peakMB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

// Issue 40: a 93-byte Radiance file whose header claims 16384 x 16384 pixels made TRay zero-fill
// 3 GB for the map before the first row failed to read. The map's floats are now not filled
// (EnvironmentMap::rgb), so only what is decoded becomes resident; and --max-memory refuses a
// map from its header alone.
TEST(EnvironmentMap, AHeaderThatLiesAboutItsSizeCostsNoMemory) {
  const fs::path dir = testDir();
  const std::string lie = (dir / "lie.hdr").string();
  std::ofstream(lie, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n"
                                          "-Y 16384 +X 16384\n"
                                       << std::string(40, '\x7f');
  const double before = peakMB();
  const std::string e = loadError(lie);
  EXPECT_NE(e.find(lie + ": cannot read pixels"), std::string::npos) << e;
  EXPECT_LT(peakMB() - before, 200.0) << "MB made resident for a map that was never there";
  // --max-memory 100: refused from the header, naming the map's share.
  try {
    loadEnvironmentMap(lie, nullptr, uint64_t(100) << 20);
    ADD_FAILURE() << "accepted";
  } catch (const Error& error) {
    const std::string said = error.what();
    EXPECT_NE(said.find("environment 3072 MB), more than --max-memory 100 MB"), std::string::npos)
        << said;
  }
}

TEST(EnvironmentMap, NotTwoToOneWarnsAndIsUsed) {
  const fs::path dir = testDir();
  std::vector<std::string> warnings;
  const auto map = loadEnvironmentMap(writeMap(dir / "square.exr", 8, 8), &warnings);
  EXPECT_EQ(map->width, 8);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("8x8, not 2:1: used as latitude-longitude anyway"), std::string::npos);
}

TEST(EnvironmentMap, CommandLineRefusesBadMapsBeforeRendering) {
  const fs::path dir = testDir();
  const std::string scene = std::string(TRAY_SOURCE_DIR) + "/scenes/whitted.gltf";
  const std::string nan = writeMap(dir / "nan.exr", 16, 8, NAN);
  for (const std::string& map : {(dir / "missing.exr").string(), nan}) {
    CliResult r = runCli(TRAY_RENDER_BIN,
                         "'" + scene + "' --env '" + map + "' -o '" + (dir / "o.exr").string() + "'",
                         dir);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(r.err.rfind("tray-render: error: " + map + ": ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "o.exr"));
  }
  // A good map renders, and the options are in the EXR metadata.
  const std::string good = writeMap(dir / "good.exr", 16, 8);
  CliResult r = runCli(TRAY_RENDER_BIN,
                       "'" + scene + "' --resolution 8x6 --env '" + good +
                           "' --env-rotate 90 --env-intensity 2 -o '" + (dir / "o.exr").string() + "'",
                       dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr e = readExrFile(dir / "o.exr");
  EXPECT_EQ(e.spec.get_string_attribute("tray:env"), good);
  EXPECT_EQ(e.spec.get_string_attribute("tray:envRotate"), "90");
  EXPECT_EQ(e.spec.get_string_attribute("tray:envIntensity"), "2");
}

/// A one-sphere glTF beside `map.exr` whose TRAY_environment is `env` (JSON).
std::string writeScene(const fs::path& dir, const std::string& env) {
  writeMap(dir / "map.exr", 16, 8);
  const std::string path = (dir / "scene.gltf").string();
  std::ofstream(path) << R"({"asset": {"version": "2.0"}, "images": [{"uri": "map.exr"}],
    "scenes": [{"nodes": [0], "extensions": {"TRAY_environment": )"
                      << env << R"(}}], "scene": 0, "nodes": [{"extensions":
    {"TRAY_shape": {"type": "sphere", "radius": 1}}}]})";
  return path;
}

TEST(EnvironmentMap, TrayEnvironmentNamesAnImageByPathOrIndex) {
  const fs::path dir = testDir();
  for (const char* image : {R"("map.exr")", "0"}) {
    const Scene s = loadGltf(
        writeScene(dir, std::string(R"({"image": )") + image + R"(, "rotation": 30, "intensity": 2})"),
        {});
    ASSERT_TRUE(s.environment.map) << image;
    EXPECT_EQ(s.environment.map->width, 16);
    EXPECT_EQ(s.environment.map->rgb[3], 0.1f);  // pixel (1, 0) red: 1 / 10
    EXPECT_EQ(s.environment.rotation, 30.0f);
    EXPECT_EQ(s.environment.intensity, 2.0f);
  }
  // The command line overrides the scene: a new map resets rotation and intensity, which
  // belonged to the scene's image; --env-rotate and --env-intensity override what is there.
  Scene s = loadGltf(writeScene(dir, R"({"image": "map.exr", "rotation": 30, "intensity": 2})"), {});
  RenderSettings settings;
  settings.set("env-rotate", 45.0f);
  applyEnvironmentOptions(s, settings, nullptr);
  EXPECT_EQ(s.environment.rotation, 45.0f);
  EXPECT_EQ(s.environment.intensity, 2.0f);
  settings.set("env", writeMap(dir / "other.exr", 32, 16));
  applyEnvironmentOptions(s, settings, nullptr);
  EXPECT_EQ(s.environment.map->width, 32);
  EXPECT_EQ(s.environment.intensity, 1.0f);
  EXPECT_EQ(s.environment.rotation, 45.0f);
}

TEST(EnvironmentMap, TrayEnvironmentImageFollowsTheUriRules) {
  const fs::path dir = testDir();
  for (const auto& [env, message] : std::vector<std::pair<std::string, std::string>>{
           {R"({"image": "../map.exr"})", "TRAY_environment image: URI '../map.exr' contains '..'"},
           {R"({"image": "nothere.exr"})", "URI 'nothere.exr': file not found"},
           {R"({"image": 3})", "image must be a file path or the index of one of the document's images"},
           {R"({"image": "map.exr", "intensity": -1})", "intensity"}}) {
    try {
      loadGltf(writeScene(dir, env), {});
      ADD_FAILURE() << env;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace tray

// ColorPipeline over a studio-style OCIO config that has no linear Rec.709 colorspace (the ACES
// configs: scene_linear is ACEScg). TRay's linear Rec.709 must enter such a config through its
// interchange role and arrive converted; before, the scene_linear space was taken for the
// working space and ACEScg output was Rec.709 data with an ACEScg tag (error up to 0.155).
// Also: the default EXR space is the config's scene_linear, a config with no way in is refused
// before rendering, the albedo AOV is converted like the beauty, and oiiotool can display
// TRay's EXRs with TRay's config ("Linear" alias).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "film/film.h"
#include "io/color.h"
#include "io/image_output.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace tray {
namespace {

const std::string kRepoConfig = std::string(TRAY_SOURCE_DIR) + "/ocio/config.ocio";

/// ACEScg as scene_linear and ACES2065-1 as aces_interchange, as the ACES studio configs do;
/// `interchange` false leaves the role out (no way in for Rec.709).
std::string writeStudioConfig(const std::string& name, bool interchange) {
  const fs::path path = test::testDir() / name;
  std::ofstream f(path);
  f << "ocio_profile_version: 2.1\n"
       "roles:\n"
       "  default: ACES - ACEScg\n"
       "  scene_linear: ACES - ACEScg\n"
       "  data: Utility - Raw\n"
    << (interchange ? "  aces_interchange: ACES - ACES2065-1\n" : "")
    << "displays:\n"
       "  sRGB:\n"
       "    - !<View> {name: Raw, colorspace: Utility - Raw}\n"
       "active_displays: [sRGB]\n"
       "active_views: [Raw]\n"
       "colorspaces:\n"
       "  - !<ColorSpace>\n"
       "    name: ACES - ACES2065-1\n"
       "    aliases: [ACES2065-1]\n"
       "    isdata: false\n"
       "  - !<ColorSpace>\n"
       "    name: ACES - ACEScg\n"
       "    aliases: [ACEScg]\n"
       "    isdata: false\n"
       "    to_scene_reference: !<BuiltinTransform> {style: ACEScg_to_ACES2065-1}\n"
       "  - !<ColorSpace>\n"
       "    name: Utility - Raw\n"
       "    isdata: true\n";
  return path.string();
}

std::array<float, 3> convert(const ColorPipeline& p, std::array<float, 3> rgb,
                             const std::string& cs) {
  p.convertFromWorking(rgb.data(), 1, 3, cs);
  return rgb;
}

TEST(ColorStudio, Rec709EntersThroughTheInterchangeRole) {
  const ColorPipeline studio(writeStudioConfig("tray-studio.ocio", true));
  const ColorPipeline repo(kRepoConfig);
  EXPECT_EQ(studio.workingSpace(), "");
  EXPECT_EQ(studio.bridgeSpace(), "ACES - ACES2065-1");
  EXPECT_EQ(studio.defaultOutputSpace(), "ACES - ACEScg");
  for (std::array<float, 3> rgb : {std::array<float, 3>{1, 0, 0}, {0, 1, 0}, {0.2f, 0.5f, 3.0f}}) {
    const auto a = convert(studio, rgb, "ACEScg"), b = convert(repo, rgb, "ACEScg");
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-5f) << c;
    // The failure this replaces: Rec.709 values written unconverted (red's G is 0.0702).
    EXPECT_GT(std::fabs(a[0] - rgb[0]) + std::fabs(a[1] - rgb[1]), 0.05f);
  }
  // Chromaticities come out as AP1's through the same bridge.
  auto xy = studio.chromaticities("ACES - ACEScg");
  ASSERT_TRUE(xy);
  EXPECT_NEAR((*xy)[0], 0.713f, 2e-3f);
  EXPECT_NEAR((*xy)[1], 0.293f, 2e-3f);
  float shown[3] = {0.5f, 0.5f, 0.5f};
  EXPECT_NO_THROW(studio.toDisplay(shown, 1, 3));
}

TEST(ColorStudio, ConfigWithNoWayInIsRefusedBeforeRendering) {
  const ColorPipeline closed(writeStudioConfig("tray-closed.ocio", false));
  try {
    closed.check("ACEScg");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("aces_interchange"), std::string::npos) << e.what();
  }
}

TEST(ColorStudio, AlbedoAovIsConvertedLikeTheBeauty) {
  setenv("OCIO", kRepoConfig.c_str(), 1);
  Film film(2, 1);
  const int albedo = film.addLayer("albedo", {"R", "G", "B"});
  for (int x = 0; x < 2; ++x) {
    float* b = film.pixel(Film::kBeauty, x, 0);
    b[0] = 1, b[1] = 0, b[2] = 0, b[3] = 1;
    float* a = film.pixel(albedo, x, 0);
    a[0] = 1, a[1] = 0, a[2] = 0;
  }
  const std::string path = (test::testDir() / "albedo-acescg.exr").string();
  ImageOutputOptions o;
  o.halfFloat = false;
  o.colorspace = "ACEScg";
  writeImage(film, path, o);
  auto in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  std::vector<float> px(size_t(spec.width) * spec.height * spec.nchannels);
  ASSERT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
  const int r = spec.channelindex("R"), ar = spec.channelindex("albedo.R"),
            ag = spec.channelindex("albedo.G");
  ASSERT_GE(ar, 0);
  EXPECT_NEAR(px[size_t(r)], 0.6131f, 1e-3f);
  EXPECT_NEAR(px[size_t(ar)], px[size_t(r)], 1e-6f);  // before: 1 (Rec.709) in an ACEScg file
  EXPECT_NEAR(px[size_t(ag)], 0.0702f, 1e-3f);
}

TEST(ColorStudio, OiiotoolDisplaysTrayExrsWithTraysConfig) {
  // OpenImageIO names an EXR's colorspace "Linear"; TRay's config aliases it to lin_rec709.
  const ColorPipeline repo(kRepoConfig);
  EXPECT_EQ(repo.canonicalName("Linear"), "lin_rec709");
  Film film(2, 2);
  const std::string exr = (test::testDir() / "oiio-display.exr").string();
  const std::string png = (test::testDir() / "oiio-display.png").string();
  setenv("OCIO", kRepoConfig.c_str(), 1);
  writeImage(film, exr, {});
  const std::string cmd = "oiiotool " + exr + " --ociodisplay sRGB Standard -o " + png;
  if (std::system("command -v oiiotool >/dev/null") != 0) GTEST_SKIP() << "no oiiotool";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  EXPECT_TRUE(fs::exists(png));
}

}  // namespace
}  // namespace tray

// ColorPipeline over the repository's OCIO config: conversions against published values,
// display encoding, config lookup ($OCIO) and errors.
#include "io/color.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "core/error.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace tray {
namespace {

const std::string kRepoConfig = std::string(TRAY_SOURCE_DIR) + "/ocio/config.ocio";

const ColorPipeline& repo() {
  static const ColorPipeline p(kRepoConfig);
  return p;
}

std::array<float, 3> converted(std::array<float, 3> rgb, const std::string& cs) {
  repo().convertFromWorking(rgb.data(), 1, 3, cs);
  return rgb;
}

TEST(Color, WorkingSpaceIsLinearRec709) {
  EXPECT_EQ(repo().workingSpace(), "lin_rec709");
  EXPECT_EQ(repo().canonicalName("Linear Rec.709 (sRGB)"), "lin_rec709");
  EXPECT_EQ(repo().canonicalName("scene_linear"), "lin_rec709");  // roles resolve too
  auto v = converted({0.25f, -0.5f, 7.0f}, "lin_rec709");
  EXPECT_FLOAT_EQ(v[0], 0.25f);
  EXPECT_FLOAT_EQ(v[1], -0.5f);
  EXPECT_FLOAT_EQ(v[2], 7.0f);
}

TEST(Color, Rec709RedToACEScg) {
  // Rec.709 -> AP1 with Bradford D65 -> ACES white: the first column of the published matrix
  // (ACES config "Utility - Linear - sRGB" to ACEScg: 0.6131, 0.0702, 0.0206).
  auto v = converted({1, 0, 0}, "ACEScg");
  EXPECT_NEAR(v[0], 0.6131f, 1e-3f);
  EXPECT_NEAR(v[1], 0.0702f, 1e-3f);
  EXPECT_NEAR(v[2], 0.0206f, 1e-3f);
  // Green and blue columns of the same matrix.
  v = converted({0, 1, 0}, "ACEScg");
  EXPECT_NEAR(v[0], 0.3395f, 1e-3f);
  EXPECT_NEAR(v[1], 0.9164f, 1e-3f);
  EXPECT_NEAR(v[2], 0.1096f, 1e-3f);
}

TEST(Color, WhiteStaysWhite) {
  // Each space's white maps to equal RGB (Bradford adaptation of D65 to the ACES white).
  for (const char* cs : {"ACEScg", "ACES2065-1", "lin_rec709"}) {
    auto v = converted({2, 2, 2}, cs);
    for (float c : v) EXPECT_NEAR(c, 2.0f, 2e-3f) << cs;
  }
}

TEST(Color, Rec709RedToACES2065_1) {
  // First column of the Rec.709 -> AP0 (Bradford) matrix: 0.4396, 0.0896, 0.0174.
  auto v = converted({1, 0, 0}, "ACES2065-1");
  EXPECT_NEAR(v[0], 0.4396f, 1e-3f);
  EXPECT_NEAR(v[1], 0.0896f, 1e-3f);
  EXPECT_NEAR(v[2], 0.0174f, 1e-3f);
}

TEST(Color, StrideLeavesOtherChannelsAlone) {
  float px[2][5] = {{1, 0, 0, 0.5f, 42}, {0, 0, 1, 0.25f, 43}};
  repo().convertFromWorking(&px[0][0], 2, 5, "ACEScg");
  EXPECT_NEAR(px[0][0], 0.6131f, 1e-3f);
  EXPECT_FLOAT_EQ(px[0][3], 0.5f);
  EXPECT_FLOAT_EQ(px[0][4], 42);
  EXPECT_NEAR(px[1][2], 0.8698f, 1e-3f);  // Rec.709 blue -> AP1 blue
  EXPECT_FLOAT_EQ(px[1][3], 0.25f);
  EXPECT_FLOAT_EQ(px[1][4], 43);
}

TEST(Color, SrgbDisplayIsThePiecewiseCurve) {
  // IEC 61966-2-1: 1.055 * 0.5^(1/2.4) - 0.055 = 0.735357; 12.92 * 0.001 in the linear toe.
  float rgb[3] = {0.5f, 0.001f, 0.0f};
  repo().toDisplay(rgb, 1, 3);
  EXPECT_NEAR(rgb[0], 0.735357f, 1e-4f);
  EXPECT_NEAR(rgb[1], 0.01292f, 1e-4f);
  EXPECT_NEAR(rgb[2], 0.0f, 1e-6f);
  // The "sRGB" texture colorspace encodes the same way.
  auto v = converted({0.5f, 0.5f, 0.5f}, "sRGB");
  EXPECT_NEAR(v[0], 0.735357f, 1e-4f);
}

TEST(Color, AcesViewToneMaps) {
  // The ACES SDR view maps scene values above 1 below display white; Standard clips them.
  float aces[3] = {4, 4, 4}, standard[3] = {4, 4, 4};
  repo().toDisplay(aces, 1, 3, "sRGB", "ACES 1.0 - SDR Video");
  repo().toDisplay(standard, 1, 3, "sRGB", "Standard");
  EXPECT_LT(aces[0], 1.0f);
  EXPECT_GT(aces[0], 0.5f);
  EXPECT_GE(standard[0], 1.0f);
}

TEST(Color, UnknownNamesListTheKnownOnes) {
  try {
    converted({1, 1, 1}, "Rec.2020-ish");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("Rec.2020-ish"), std::string::npos) << m;
    EXPECT_NE(m.find("ACEScg"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  float rgb[3] = {};
  EXPECT_THROW(repo().toDisplay(rgb, 1, 3, "DCI-P3"), Error);
  EXPECT_THROW(repo().toDisplay(rgb, 1, 3, "sRGB", "Filmic"), Error);
}

TEST(Color, Chromaticities) {
  auto rec709 = repo().chromaticities("lin_rec709");
  ASSERT_TRUE(rec709);
  EXPECT_FLOAT_EQ((*rec709)[0], 0.64f);
  EXPECT_FLOAT_EQ((*rec709)[7], 0.3290f);
  auto ap1 = repo().chromaticities("lin_ap1");  // by alias
  ASSERT_TRUE(ap1);
  EXPECT_FLOAT_EQ((*ap1)[0], 0.713f);
  EXPECT_FLOAT_EQ((*ap1)[6], 0.32168f);
  auto ap0 = repo().chromaticities("ACES2065-1");
  ASSERT_TRUE(ap0);
  EXPECT_FLOAT_EQ((*ap0)[5], -0.077f);
  EXPECT_FALSE(repo().chromaticities("raw"));
  // CIE-XYZ-D65 is no known name: derived through OCIO, XYZ's primaries are (1,0), (0,1),
  // (0,0), and its RGB (1,1,1) is the equal-energy white (1/3, 1/3).
  auto xyz = repo().chromaticities("CIE-XYZ-D65");
  ASSERT_TRUE(xyz);
  EXPECT_NEAR((*xyz)[0], 1.0f, 1e-3f);
  EXPECT_NEAR((*xyz)[3], 1.0f, 1e-3f);
  EXPECT_NEAR((*xyz)[4], 0.0f, 1e-3f);
  EXPECT_NEAR((*xyz)[5], 0.0f, 1e-3f);
  EXPECT_NEAR((*xyz)[6], 1.0f / 3, 1e-3f);
  EXPECT_NEAR((*xyz)[7], 1.0f / 3, 1e-3f);
}

TEST(Color, MissingConfigNamesTheFile) {
  const std::string missing = (test::testDir() / "no_such_config.ocio").string();
  try {
    ColorPipeline p(missing);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing + ": ", 0), 0u) << e.what();
  }
}

TEST(Color, HonoursOcioEnvironment) {
  // A copy of the repo's config under another name: the pipeline must come from $OCIO.
  // This is the only test here that touches instance(), which is created on first use.
  const std::string copy = (test::testDir() / "color_test_config.ocio").string();
  fs::copy_file(kRepoConfig, copy, fs::copy_options::overwrite_existing);
  ASSERT_EQ(setenv("OCIO", copy.c_str(), 1), 0);
  EXPECT_EQ(ColorPipeline::defaultConfigPath(), copy);
  const ColorPipeline& p = ColorPipeline::instance();
  EXPECT_EQ(p.configPath(), copy);
  float rgb[3] = {1, 0, 0};
  p.convertFromWorking(rgb, 1, 3, "ACEScg");
  EXPECT_NEAR(rgb[0], 0.6131f, 1e-3f);
  unsetenv("OCIO");
  // Without $OCIO the default is an existing config (beside the binary or in the source tree).
  EXPECT_TRUE(fs::is_regular_file(ColorPipeline::defaultConfigPath()));
}

}  // namespace
}  // namespace tray

// writeImage: EXR layers, precision, colour metadata and windows read back with OIIO; PNG/JPEG
// display encoding; atomic writes and one-line errors. Files go to the test's own testDir().
#include "io/image_output.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include "core/error.h"
#include "tests/exr_read.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace tray {
namespace {

// Pin the config: a developer's own $OCIO must not change what these tests expect.
const bool kRepoConfig =
    setenv("OCIO", (std::string(TRAY_SOURCE_DIR) + "/ocio/config.ocio").c_str(), 1) == 0;

/// 3x2 film; beauty values include > 1 and negative; an "N" layer and a one-channel "Z" layer.
Film testFilm() {
  Film film(3, 2);
  const int n = film.addLayer("N", {"X", "Y", "Z"}), z = film.addLayer("Z", {"Z"});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      float* p = film.pixel(Film::kBeauty, x, y);
      p[0] = 0.25f * x + y * 3.5f, p[1] = -0.125f * x, p[2] = 100.0f + x, p[3] = 0.5f * y;
      float* nrm = film.pixel(n, x, y);
      nrm[0] = 0.6f, nrm[1] = -0.8f, nrm[2] = float(y);
      film.pixel(z, x, y)[0] = 1234.567f + x;  // needs float: half's step at 1024 is 1
    }
  return film;
}

float halfTolerance(float v) {
  return 1e-3f * std::max(1.0f, std::abs(v));
}

std::vector<fs::path> filesIn(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename());
  return out;
}

std::string contents(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

TEST(ImageOutput, ExrRoundTrip) {
  ASSERT_TRUE(kRepoConfig);
  const fs::path path = test::testDir() / "beauty.exr";
  const Film film = testFilm();
  ImageOutputOptions o;
  o.stringMetadata = {{"tray:integrator", "path"}};
  o.floatMetadata = {{"tray:spp", 64.0f}};
  std::array<float, 16> m{};
  for (int i = 0; i < 16; ++i) m[i] = float(i) - 3.5f;
  o.matrixMetadata = {{"worldToCamera", m}};
  writeImage(film, path.string(), o);

  const test::Exr r = test::readExrFile(path);
  ASSERT_EQ(r.spec.nchannels, 8);
  for (const char* name : {"R", "G", "B", "A", "N.X", "N.Y", "N.Z", "Z"})
    EXPECT_GE(r.channel(name), 0) << name;
  EXPECT_EQ(r.spec.channelnames[r.spec.alpha_channel], "A");
  for (int c = 0; c < 8; ++c) {
    const std::string& name = r.spec.channelnames[c];
    const OIIO::TypeDesc t = r.spec.channelformat(c);
    EXPECT_EQ(t, name == "Z" ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF) << name;
  }
  const int nIndex = film.findLayer("N"), zIndex = film.findLayer("Z");
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      const float* p = film.pixel(Film::kBeauty, x, y);
      const char* rgba[] = {"R", "G", "B", "A"};
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(r.at(x, y, rgba[c]), p[c], halfTolerance(p[c])) << rgba[c] << x << y;
      EXPECT_NEAR(r.at(x, y, "N.Y"), film.pixel(nIndex, x, y)[1], 1e-3f);
      EXPECT_NEAR(r.at(x, y, "N.Z"), film.pixel(nIndex, x, y)[2], 1e-3f);
      EXPECT_FLOAT_EQ(r.at(x, y, "Z"), film.pixel(zIndex, x, y)[0]);
    }

  EXPECT_EQ(r.spec.get_string_attribute("colorspace"), "lin_rec709");
  // (OIIO keeps "oiio:ColorSpace" to itself: its EXR reader reports "Linear" whatever was set.)
  EXPECT_EQ(r.spec.get_string_attribute("compression"), "zip");
  const OIIO::ParamValue* chroma = r.spec.find_attribute("chromaticities");
  ASSERT_TRUE(chroma);
  ASSERT_EQ(chroma->type(), OIIO::TypeDesc(OIIO::TypeDesc::FLOAT, 8));
  const float rec709[8] = {0.64f, 0.33f, 0.30f, 0.60f, 0.15f, 0.06f, 0.3127f, 0.3290f};
  for (int i = 0; i < 8; ++i)
    EXPECT_FLOAT_EQ(static_cast<const float*>(chroma->data())[i], rec709[i]);
  EXPECT_EQ(r.spec.get_string_attribute("tray:integrator"), "path");
  EXPECT_FLOAT_EQ(r.spec.get_float_attribute("tray:spp"), 64.0f);
  const OIIO::ParamValue* w2c = r.spec.find_attribute("worldToCamera");
  ASSERT_TRUE(w2c);
  ASSERT_EQ(w2c->type(), OIIO::TypeMatrix44);
  for (int i = 0; i < 16; ++i) EXPECT_FLOAT_EQ(static_cast<const float*>(w2c->data())[i], m[i]);
  EXPECT_EQ(filesIn(path.parent_path()).size(), 1u);  // no temporary left behind
}

TEST(ImageOutput, FloatOptionWritesFloat) {
  const fs::path path = test::testDir() / "float.exr";
  const Film film = testFilm();
  ImageOutputOptions o;
  o.halfFloat = false;
  writeImage(film, path.string(), o);
  const test::Exr r = test::readExrFile(path);
  for (int c = 0; c < r.spec.nchannels; ++c)
    EXPECT_EQ(r.spec.channelformat(c), OIIO::TypeDesc::FLOAT);
  // 0.25 * 1 + 3.5 is exact either way; 100 + x + tiny is not representable in half.
  EXPECT_FLOAT_EQ(r.at(1, 1, "R"), film.pixel(Film::kBeauty, 1, 1)[0]);
}

TEST(ImageOutput, HalfIsTheDefault) {
  const fs::path path = test::testDir() / "half.exr";
  Film film(2, 2);
  film.pixel(Film::kBeauty, 0, 0)[0] = 0.1f;  // half: 0.0999755859375
  writeImage(film, path.string());
  const test::Exr r = test::readExrFile(path);
  EXPECT_EQ(r.spec.channelformat(0), OIIO::TypeDesc::HALF);
  EXPECT_NE(r.at(0, 0, "R"), 0.1f);
  EXPECT_NEAR(r.at(0, 0, "R"), 0.1f, 1e-4f);
}

TEST(ImageOutput, HalfClampsBeyond65504InsteadOfInfinity) {
  // Half's largest finite value is 65504; 1e6 used to become +Inf silently. Each channel is
  // clamped on its own; float output keeps every value.
  const fs::path dir = test::testDir();
  Film film(2, 1);
  float* p = film.pixel(Film::kBeauty, 0, 0);
  p[0] = 1e6f, p[1] = -1e6f, p[2] = 65504.0f, p[3] = 1.0f;
  float* q = film.pixel(Film::kBeauty, 1, 0);
  q[0] = 0.5f, q[1] = 70000.0f, q[2] = 2.0f, q[3] = 1.0f;
  EXPECT_EQ(writeImage(film, (dir / "half.exr").string()), 3u);
  const test::Exr h = test::readExrFile(dir / "half.exr");
  EXPECT_EQ(h.at(0, 0, "R"), 65504.0f);
  EXPECT_EQ(h.at(0, 0, "G"), -65504.0f);
  EXPECT_EQ(h.at(0, 0, "B"), 65504.0f);
  EXPECT_EQ(h.at(1, 0, "R"), 0.5f);
  EXPECT_EQ(h.at(1, 0, "G"), 65504.0f);
  EXPECT_EQ(h.at(1, 0, "B"), 2.0f);
  for (float v : h.pixels) EXPECT_TRUE(std::isfinite(v));

  ImageOutputOptions o;
  o.halfFloat = false;
  EXPECT_EQ(writeImage(film, (dir / "float.exr").string(), o), 0u);
  EXPECT_EQ(test::readExrFile(dir / "float.exr").at(0, 0, "R"), 1e6f);
  EXPECT_EQ(halfClampWarning("a.exr", 3),
            "a.exr: 3 value(s) beyond half float's range clamped to +-65504 (use --float to keep "
            "them)");
}

TEST(ImageOutput, DataAndDisplayWindows) {
  const fs::path path = test::testDir() / "region.exr";
  ImageOutputOptions o;
  o.fullWidth = 20, o.fullHeight = 10, o.xOffset = 5, o.yOffset = 7;
  writeImage(testFilm(), path.string(), o);
  const test::Exr r = test::readExrFile(path);
  EXPECT_EQ(r.spec.x, 5);
  EXPECT_EQ(r.spec.y, 7);
  EXPECT_EQ(r.spec.width, 3);
  EXPECT_EQ(r.spec.height, 2);
  EXPECT_EQ(r.spec.full_x, 0);
  EXPECT_EQ(r.spec.full_y, 0);
  EXPECT_EQ(r.spec.full_width, 20);
  EXPECT_EQ(r.spec.full_height, 10);
}

TEST(ImageOutput, AcesCgConvertsOnlyTheBeautyRgb) {
  const fs::path path = test::testDir() / "acescg.exr";
  Film film(2, 1);
  const int n = film.addLayer("N", {"X", "Y", "Z"});
  float* red = film.pixel(Film::kBeauty, 0, 0);
  red[0] = 1, red[1] = 0, red[2] = 0, red[3] = 1;
  float* white = film.pixel(Film::kBeauty, 1, 0);
  white[0] = white[1] = white[2] = 3, white[3] = 0.25f;
  for (int x = 0; x < 2; ++x) film.pixel(n, x, 0)[0] = 1;  // (1, 0, 0) as a normal: unchanged
  ImageOutputOptions o;
  o.colorspace = "ACEScg";
  o.halfFloat = false;
  writeImage(film, path.string(), o);
  const test::Exr r = test::readExrFile(path);
  EXPECT_NEAR(r.at(0, 0, "R"), 0.6131f, 1e-3f);
  EXPECT_NEAR(r.at(0, 0, "G"), 0.0702f, 1e-3f);
  EXPECT_NEAR(r.at(0, 0, "B"), 0.0206f, 1e-3f);
  EXPECT_FLOAT_EQ(r.at(0, 0, "A"), 1.0f);
  for (const char* c : {"R", "G", "B"}) EXPECT_NEAR(r.at(1, 0, c), 3.0f, 3e-3f) << c;
  EXPECT_FLOAT_EQ(r.at(1, 0, "A"), 0.25f);
  EXPECT_FLOAT_EQ(r.at(0, 0, "N.X"), 1.0f);
  EXPECT_FLOAT_EQ(r.at(0, 0, "N.Y"), 0.0f);
  EXPECT_EQ(r.spec.get_string_attribute("colorspace"), "ACEScg");
  const OIIO::ParamValue* chroma = r.spec.find_attribute("chromaticities");
  ASSERT_TRUE(chroma);
  const float ap1[8] = {0.713f, 0.293f, 0.165f, 0.830f, 0.128f, 0.044f, 0.32168f, 0.33767f};
  for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(static_cast<const float*>(chroma->data())[i], ap1[i]);
}

TEST(ImageOutput, PngIsDisplayReferredSrgb) {
  const fs::path path = test::testDir() / "beauty.png";
  Film film(3, 1);
  const float values[3] = {0.5f, 2.0f, -1.0f};
  for (int x = 0; x < 3; ++x) {
    float* p = film.pixel(Film::kBeauty, x, 0);
    p[0] = p[1] = p[2] = values[x], p[3] = 1;
  }
  writeImage(film, path.string());
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  ASSERT_EQ(in->spec().nchannels, 3);
  EXPECT_EQ(in->spec().format, OIIO::TypeDesc::UINT8);
  unsigned char px[9];
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px));
  // sRGB: 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5; above 1 clips; negative clamps to 0.
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(px[c], 188, 1);
    EXPECT_EQ(px[3 + c], 255);
    EXPECT_EQ(px[6 + c], 0);
  }
}

TEST(ImageOutput, JpegThroughTheDisplayView) {
  const fs::path path = test::testDir() / "beauty.JPG";  // extensions are case-insensitive
  Film film(16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      float* p = film.pixel(Film::kBeauty, x, y);
      p[0] = p[1] = p[2] = 0.5f, p[3] = 1;
    }
  writeImage(film, path.string());
  auto in = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(std::string(in->format_name()), "jpeg");
  std::vector<unsigned char> px(16 * 16 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, px.data()));
  EXPECT_NEAR(px[100], 188, 2);  // flat grey survives JPEG almost exactly
}

TEST(ImageOutput, MissingFolderThrowsAndCreatesNothing) {
  const fs::path dir = test::testDir();
  const std::string path = (dir / "no_such_folder" / "out.exr").string();
  try {
    writeImage(testFilm(), path);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(path + ": ", 0), 0u) << m;
    EXPECT_NE(m.find("does not exist"), std::string::npos) << m;
  }
  EXPECT_TRUE(filesIn(dir).empty());
}

TEST(ImageOutput, UnsupportedExtensionThrows) {
  const fs::path dir = test::testDir();
  for (const char* name : {"out.tif", "out", "out.exr.bak"}) {
    const std::string path = (dir / name).string();
    try {
      writeImage(testFilm(), path);
      FAIL() << "no error for " << name;
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind(path + ": unsupported output format", 0), 0u) << m;
    }
  }
  EXPECT_TRUE(filesIn(dir).empty());
}

TEST(ImageOutput, BadColorspaceKeepsTheExistingFile) {
  const fs::path dir = test::testDir();
  const fs::path path = dir / "keep.exr";
  writeImage(testFilm(), path.string());
  const std::string before = contents(path);
  ImageOutputOptions o;
  o.colorspace = "no-such-space";
  try {
    writeImage(testFilm(), path.string(), o);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(path.string() + ": unknown colorspace 'no-such-space'", 0), 0u) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  EXPECT_EQ(contents(path), before);
  EXPECT_EQ(filesIn(dir).size(), 1u);
}

TEST(ImageOutput, FailedWriteLeavesTheExistingFileIntact) {
  // A real mid-write failure: cap this process's file size (RLIMIT_FSIZE) below the new
  // image's size, so write(2) fails with EFBIG part-way through the temporary file.
  const fs::path dir = test::testDir();
  const fs::path path = dir / "big.exr";
  writeImage(testFilm(), path.string());
  const std::string before = contents(path);

  Film noisy(256, 256);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0, 1000);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      for (int c = 0; c < 4; ++c) noisy.pixel(Film::kBeauty, x, y)[c] = u(rng);  // incompressible
  ImageOutputOptions o;
  o.halfFloat = false;

  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit capped = old;
  capped.rlim_cur = 64 * 1024;
  auto oldHandler = signal(SIGXFSZ, SIG_IGN);  // else the kernel kills the process
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &capped), 0);
  std::string message;
  try {
    writeImage(noisy, path.string(), o);
  } catch (const Error& e) {
    message = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &old);
  signal(SIGXFSZ, oldHandler);

  EXPECT_EQ(message.rfind(path.string() + ": writing failed", 0), 0u)
      << "message: '" << message << "'";
  EXPECT_EQ(contents(path), before);
  EXPECT_EQ(filesIn(dir).size(), 1u);  // the partial temporary is gone
}

TEST(ImageOutput, WriteImagesIsAllOrNothing) {
  // The second output fails (an unknown display for the PNG) after the first is written under
  // its temporary name: neither file changes, no temporary is left.
  const fs::path dir = test::testDir();
  const fs::path exr = dir / "a.exr", png = dir / "a.png";
  writeImages(testFilm(), {exr.string(), png.string()});
  const std::string exrBefore = contents(exr), pngBefore = contents(png);
  Film other = testFilm();
  other.pixel(Film::kBeauty, 0, 0)[0] = 7.0f;
  ImageOutputOptions bad;
  bad.display = "no-such-display";
  EXPECT_THROW(writeImages(other, {exr.string(), png.string()}, bad), Error);
  EXPECT_EQ(contents(exr), exrBefore);
  EXPECT_EQ(contents(png), pngBefore);
  EXPECT_EQ(filesIn(dir).size(), 2u);
  // Both written when both can be.
  writeImages(other, {exr.string(), png.string()});
  EXPECT_NE(contents(exr), exrBefore);
}

TEST(ImageOutput, ChannelNames) {
  EXPECT_EQ(exrChannelName({"", {"R"}, {}}, "R"), "R");
  EXPECT_EQ(exrChannelName({"Z", {"Z"}, {}}, "Z"), "Z");
  EXPECT_EQ(exrChannelName({"N", {"X", "Y", "Z"}, {}}, "X"), "N.X");
  EXPECT_EQ(exrChannelName({"albedo", {"R", "G", "B"}, {}}, "G"), "albedo.G");
  EXPECT_EQ(exrChannelName({"objectid", {"id"}, {}}, "id"), "objectid.id");
}

}  // namespace
}  // namespace tray

// AOV and Cryptomatte layers as a compositor sees them: a render written to EXR and read back
// with OIIO, values checked at pixels whose answer is known from the scene's geometry.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "accel/registry.h"
#include "film/aov.h"
#include "film/cryptomatte.h"
#include "integrators/registry.h"
#include "io/image_output.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "tests/scene_builder.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace tray {
namespace {

using namespace tray::test;

const bool kRepoConfig =
    setenv("OCIO", (std::string(TRAY_SOURCE_DIR) + "/ocio/config.ocio").c_str(), 1) == 0;

/// Every channel of an EXR as float, by name.
struct ExrImage {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;
  float at(const std::string& channel, int x, int y) const {
    auto it = std::find(spec.channelnames.begin(), spec.channelnames.end(), channel);
    EXPECT_NE(it, spec.channelnames.end()) << channel;
    if (it == spec.channelnames.end()) return NAN;
    const size_t c = size_t(it - spec.channelnames.begin());
    return pixels[(size_t(y) * spec.width + x) * spec.nchannels + c];
  }
};

ExrImage readExr(const std::string& path) {
  ExrImage img;
  auto in = OIIO::ImageInput::open(path);
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return img;
  img.spec = in->spec();
  img.pixels.resize(size_t(img.spec.image_pixels()) * img.spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, img.spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data()))
      << in->geterror();
  return img;
}

/// Floor plane (shape0), unit sphere (shape1) at (0, 1, -4) and a second sphere (shape2)
/// touching it on the right, from a camera at (0, 1, 0) looking down -Z; 4x4 grid spp, box filter.
class AovExr : public ::testing::Test {
 protected:
  static constexpr int W = 33, H = 33;
  Scene scene;
  std::optional<PreparedScene> prepared;
  ExrImage image;

  void SetUp() override {
    int floorMat = addMaterial(scene, diffuse(Color(0.2f)));
    int ballMat = addMaterial(scene, diffuse(Color(0.9f, 0.5f, 0.1f)));
    addShape(scene, std::make_shared<Plane>(), Mat4::identity(), floorMat);
    addSphere(scene, {0, 1, -4}, 1.0f, ballMat);
    addSphere(scene, {2, 1, -4}, 1.0f, ballMat);
    scene.primitives[2].name = "right ball \"two\"";  // quotes must survive the JSON manifest
    scene.finalize();
    RenderSettings settings;
    settings.set("spp", 16);
    settings.set("pixel-sampler", "grid");
    settings.set("filter", "box");
    RenderOptions opt;
    opt.aovs = AovSet::parse("all");
    prepared.emplace(scene, lookAt({0, 1, 0}, {0, 1, -1}, 1.0f), ImageSize{W, H});
    Film film = prepared->render(settings, opt);
    const std::string path = (test::testDir() / "aovs.exr").string();
    writeImage(film, path);
    image = readExr(path);
  }
};

TEST_F(AovExr, DepthNormalPositionAndIdsAtKnownPixels) {
  // Centre pixel: the sphere's front point (0, 1, -3) up to the grid offsets of a quarter pixel
  // (depth and normal: means of the 16 samples; position: the first's); its normal points back
  // at the camera.
  EXPECT_NEAR(image.at("Z", 16, 16), 3.0f, 0.01f);
  EXPECT_NEAR(image.at("N.Z", 16, 16), 1.0f, 0.01f);
  EXPECT_NEAR(image.at("P.Z", 16, 16), -3.0f, 0.01f);
  EXPECT_EQ(image.at("objectid.id", 16, 16), 1.0f);
  EXPECT_EQ(image.at("materialid.id", 16, 16), 1.0f);
  EXPECT_NEAR(image.at("albedo.G", 16, 16), 0.5f, 1e-3f);
  EXPECT_EQ(image.at("samples.count", 16, 16), 16.0f);
  // Bottom row: the floor at the mean depth t |d| of the 16 grid samples' rays (the 4x4 cell
  // centres; box filter: equal weights), normal +Y.
  double depth = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const Ray r = prepared->camera().generateRay(16 + (i + 0.5f) / 4, 32 + (j + 0.5f) / 4);
      depth += -r.o.y / r.d.y * length(r.d) / 16;
    }
  EXPECT_NEAR(image.at("Z", 16, 32), depth, 1e-3f);
  EXPECT_NEAR(image.at("N.Y", 16, 32), 1.0f, 1e-3f);
  EXPECT_NEAR(image.at("P.Y", 16, 32), 0.0f, 1e-4f);
  EXPECT_EQ(image.at("objectid.id", 16, 32), 0.0f);
  // Sky: infinite depth, no object.
  EXPECT_TRUE(std::isinf(image.at("Z", 16, 0)));
  EXPECT_EQ(image.at("objectid.id", 16, 0), -1.0f);
}

TEST_F(AovExr, CryptomatteLayersAndManifestReadBack) {
  for (const char* c : {"CryptoObject00.R", "CryptoObject02.A", "CryptoMaterial01.G"}) {
    auto& names = image.spec.channelnames;
    EXPECT_NE(std::find(names.begin(), names.end(), c), names.end()) << c;
    EXPECT_EQ(
        image.spec.channelformat(int(std::find(names.begin(), names.end(), c) - names.begin())),
        OIIO::TypeDesc::FLOAT)
        << c;
  }
  const std::string key = "cryptomatte/" + Cryptomatte::metadataKey("CryptoObject") + "/";
  EXPECT_EQ(image.spec.get_string_attribute(key + "name"), "CryptoObject");
  EXPECT_EQ(image.spec.get_string_attribute(key + "hash"), "MurmurHash3_32");
  EXPECT_EQ(image.spec.get_string_attribute(key + "conversion"), "uint32_to_float32");
  const nlohmann::json manifest =
      nlohmann::json::parse(image.spec.get_string_attribute(key + "manifest"));
  ASSERT_TRUE(manifest.is_object());
  EXPECT_EQ(manifest.size(), scene.primitives.size());
  for (const Primitive& p : scene.primitives) {
    ASSERT_TRUE(manifest.contains(p.name)) << p.name;
    const uint32_t hash = std::stoul(manifest[p.name].get<std::string>(), nullptr, 16);
    EXPECT_EQ(std::bit_cast<float>(hash), cryptomatteId(p.name));
  }

  // Every pixel's coverage sums to 1; in covered pixels (alpha 1) no rank is the sky's id 0.
  int covered = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      double sum = 0;
      bool sky = false;
      for (int l = 0; l < 3; ++l)
        for (const char* pair : {"RG", "BA"}) {
          const std::string layer = "CryptoObject0" + std::to_string(l) + ".";
          const float cov = image.at(layer + pair[1], x, y);
          sum += cov;
          sky = sky || (cov > 0 && image.at(layer + pair[0], x, y) == 0.0f);
        }
      EXPECT_NEAR(sum, 1.0, 1e-5) << x << "," << y;
      if (image.at("A", x, y) == 1.0f) {
        ++covered;
        EXPECT_FALSE(sky) << x << "," << y;
      }
    }
  EXPECT_GT(covered, W * H / 3);

  // The centre shows the first sphere alone; the id is its name's hash.
  EXPECT_EQ(image.at("CryptoObject00.R", 16, 16), cryptomatteId("shape1"));
  EXPECT_FLOAT_EQ(image.at("CryptoObject00.G", 16, 16), 1.0f);
  // The second sphere peeks out beside the first one's silhouette (about 7.8 pixels right of
  // the centre): along the centre row, some pixel holds both, with fractional coverages.
  bool edge = false;
  for (int x = 17; x < W; ++x) {
    const float a = image.at("CryptoObject00.R", x, 16), b = image.at("CryptoObject00.B", x, 16);
    const float ca = image.at("CryptoObject00.G", x, 16), cb = image.at("CryptoObject00.A", x, 16);
    if (((a == cryptomatteId("shape1") && b == cryptomatteId(scene.primitives[2].name)) ||
         (b == cryptomatteId("shape1") && a == cryptomatteId(scene.primitives[2].name))) &&
        ca > 0.05f && cb > 0.05f && ca < 0.95f && cb < 0.95f)
      edge = true;
  }
  EXPECT_TRUE(edge);
}

}  // namespace
}  // namespace tray

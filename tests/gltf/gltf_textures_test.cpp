// Textures from glTF files: decoding (sRGB, PNG/JPEG only, caps), samplers, embedded and
// external images, the errors bad images give, and the Khronos texture test assets rendered.
#include "gltf/gltf_textures.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "core/error.h"
#include "gltf/gltf_images.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "tests/base64.h"
#include "tests/gltf/tiny_doc.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

namespace fs = std::filesystem;

const fs::path kSamples = fs::path(TRAY_SHARED_DIR) / "gltf-samples";

using test::freshFolder;

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

/// Writes an 8-bit RGB image with OIIO (the format follows the extension).
void writeImage(const fs::path& path, int w, int h, const std::vector<unsigned char>& rgb) {
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
  ASSERT_TRUE(out->open(path.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, rgb.data()));
  out->close();
}

using tray::test::base64;

/// A document with one material using image `uri` as base colour and metallic-roughness
/// texture: no meshes are needed, every material's textures are decoded.
std::string materialDoc(const std::string& uri, const std::string& sampler = "{}") {
  return R"({"asset":{"version":"2.0"},"images":[{"uri":")" + uri + R"("}],"samplers":[)" +
         sampler +
         R"(],"textures":[{"source":0,"sampler":0}],"materials":[{"pbrMetallicRoughness":{)"
         R"("baseColorTexture":{"index":0},"metallicRoughnessTexture":{"index":0}}}]})";
}

const std::vector<unsigned char> kPixels = {128, 64, 255, 0, 10, 200};  // 2 x 1 RGB

/// A loaded texture's linear float RGB, row by row (the loader keeps the file's codes).
std::vector<float> floats(const TextureImage& im) {
  std::vector<float> out(size_t(im.width) * size_t(im.height) * 3);
  for (int y = 0; y < im.height; ++y) im.row(y, out.data() + size_t(y) * size_t(im.width) * 3);
  return out;
}

TEST(GltfTextures, BaseColorIsSrgbDecodedAndMetallicRoughnessIsNot) {
  fs::path dir = freshFolder();
  writeImage(dir / "tex.png", 2, 1, kPixels);
  writeText(dir / "scene.gltf",
            materialDoc("tex.png", R"({"wrapS":33071,"wrapT":33648,"magFilter":9728,)"
                                   R"("minFilter":9984})"));
  Scene s = loadGltf((dir / "scene.gltf").string());
  ASSERT_EQ(s.textures.size(), 2u);  // one image, decoded once as sRGB and once as linear
  const Material& m = s.materials[0];
  const TextureImage& srgb = s.textures[size_t(m.baseColorTexture.image)];
  const TextureImage& linear = s.textures[size_t(m.metallicRoughnessTexture.image)];
  EXPECT_TRUE(srgb.srgb);
  EXPECT_FALSE(linear.srgb);
  ASSERT_EQ(srgb.width, 2);
  ASSERT_EQ(srgb.height, 1);
  // IEC 61966-2-1 values: 128 -> 0.21586, 64 -> 0.05127, 10 -> 0.003035, 200 -> 0.57758.
  const float want[6] = {0.2158605f, 0.0512695f, 1.0f, 0.0f, 0.0030353f, 0.5775804f};
  const std::vector<float> srgbFloats = floats(srgb), linearFloats = floats(linear);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(srgbFloats[size_t(i)], want[i], 1e-5f) << i;
    EXPECT_NEAR(linearFloats[size_t(i)], kPixels[size_t(i)] / 255.0f, 1e-6f) << i;
  }
  // Decoded once: both views read the same codes.
  EXPECT_EQ(srgb.codes, linear.codes);
  ASSERT_TRUE(srgb.codes);
  EXPECT_EQ(srgb.codes->bytes, kPixels);
  EXPECT_EQ(m.baseColorTexture.wrapS, TextureWrap::kClampToEdge);
  EXPECT_EQ(m.baseColorTexture.wrapT, TextureWrap::kMirroredRepeat);
  EXPECT_EQ(m.baseColorTexture.magFilter, TextureFilter::kNearest);
  EXPECT_EQ(m.baseColorTexture.minFilter, TextureFilter::kNearestMipmapNearest);
}

TEST(GltfTextures, DataUriImagesDecodeLikeFiles) {
  fs::path dir = freshFolder();
  writeImage(dir / "tex.png", 2, 1, kPixels);
  writeText(dir / "scene.gltf",
            materialDoc("data:image/png;base64," + base64(readBytes(dir / "tex.png"))));
  Scene s = loadGltf((dir / "scene.gltf").string());
  ASSERT_EQ(s.textures.size(), 2u);
  EXPECT_NEAR(floats(s.textures[0])[0], 0.2158605f, 1e-5f);
  EXPECT_EQ(s.textures[0].name, "image 0");
}

TEST(GltfTextures, JpegIsAccepted) {
  fs::path dir = freshFolder();
  writeImage(dir / "tex.jpg", 8, 8, std::vector<unsigned char>(8 * 8 * 3, 200));
  writeText(dir / "scene.gltf", materialDoc("tex.jpg"));
  Scene s = loadGltf((dir / "scene.gltf").string());
  ASSERT_EQ(s.textures.size(), 2u);
  EXPECT_NEAR(floats(s.textures[1])[0], 200 / 255.0f, 2.0f / 255);  // JPEG is lossy
}

/// Loads dir/scene.gltf expecting a one-line input error that names `mention`.
void expectImageError(const fs::path& dir, const std::string& mention, const std::string& what) {
  const std::string path = (dir / "scene.gltf").string();
  try {
    loadGltf(path);
    FAIL() << "loaded without error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.kind(), Error::Kind::kInput);
    EXPECT_EQ(message.rfind(path, 0), 0u) << message;  // starts with the scene file
    EXPECT_NE(message.find(mention), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

TEST(GltfTextures, MissingImageFileIsAnError) {
  fs::path dir = freshFolder();
  writeText(dir / "scene.gltf", materialDoc("missing.png"));
  expectImageError(dir, "missing.png", "not found");
}

TEST(GltfTextures, FormatsGltfDoesNotAllowAreRefused) {
  // A real BMP (OIIO could read it) and a text file with a .png name.
  fs::path dir = freshFolder();
  writeImage(dir / "tex.bmp", 2, 1, kPixels);
  writeText(dir / "scene.gltf", materialDoc("tex.bmp"));
  expectImageError(dir, "tex.bmp", "not a PNG or JPEG");
  writeText(dir / "fake.png", "GIF89a this is not a PNG");
  writeText(dir / "scene.gltf", materialDoc("fake.png"));
  expectImageError(dir, "fake.png", "not a PNG or JPEG");
}

uint32_t crc32(const std::string& bytes) {  // PNG chunk CRC (ISO 3309), bit by bit
  uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xffffffffu;
}

std::string be32(uint32_t v) {
  return {char(v >> 24), char(v >> 16 & 255), char(v >> 8 & 255), char(v & 255)};
}

std::string chunk(const std::string& type, const std::string& data) {
  return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
}

TEST(GltfTextures, OversizedImageIsRefusedFromItsHeader) {
  // A PNG whose header claims 9000 x 9000 pixels, with a token IDAT: refused before decoding.
  std::string ihdr = be32(9000) + be32(9000) + std::string("\x08\x02\x00\x00\x00", 5);
  std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) +
                    chunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) +
                    chunk("IEND", "");
  fs::path dir = freshFolder();
  writeText(dir / "huge.png", png);
  writeText(dir / "scene.gltf", materialDoc("huge.png"));
  expectImageError(dir, "huge.png", "9000x9000 pixels exceeds the limit");
}

TEST(GltfTextures, InvalidSamplerValueIsAnError) {
  fs::path dir = freshFolder();
  writeImage(dir / "tex.png", 2, 1, kPixels);
  writeText(dir / "scene.gltf", materialDoc("tex.png", R"({"wrapS":1234})"));
  expectImageError(dir, "sampler 0", "invalid wrap mode 1234");
}

TEST(GltfTextures, CommandLineExitsWithCode2OnABadImage) {
  fs::path dir = freshFolder();
  writeImage(dir / "tex.bmp", 2, 1, kPixels);
  writeText(dir / "scene.gltf", materialDoc("tex.bmp"));
  const std::string cmd = std::string(TRAY_RENDER_BIN) + " -q -o " + (dir / "out.exr").string() +
                          " " + (dir / "scene.gltf").string() + " 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  ASSERT_TRUE(pipe);
  std::string output;
  char buffer[512];
  while (size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) output.append(buffer, n);
  int status = ::pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(output.find("not a PNG or JPEG"), std::string::npos) << output;
  EXPECT_EQ(std::count(output.begin(), output.end(), '\n'), 1) << output;
  EXPECT_FALSE(fs::exists(dir / "out.exr"));
}

// ---------------------------------------------------------------------------------------------
// Khronos assets, rendered by Whitted under a white ambient light and no lamps: every pixel
// shows the material's (textured) diffuse colour, i.e. the base colour (both are dielectric).

struct Render {
  Scene scene;
  Film film;
  int objectLayer, materialLayer;
  Color at(int x, int y) const {
    const float* p = film.pixel(Film::kBeauty, x, y);
    return {p[0], p[1], p[2]};
  }
  int object(int x, int y) const { return int(film.pixel(objectLayer, x, y)[0]); }
  int material(int x, int y) const { return int(film.pixel(materialLayer, x, y)[0]); }
};

Render renderAmbient(const std::string& file, int w, int h, int threads = 0) {
  Scene scene = loadGltf((kSamples / file).string());
  scene.environment.ambient = Color(1.0f);
  CameraDesc cam = chooseCamera(scene, -1);
  RenderSettings settings;
  settings.set("integrator", "whitted");
  const PreparedScene prepared(scene, cam, {w, h});
  const RenderContext ctx = prepared.context(settings);
  auto integrator = makeIntegrator(ctx);
  Film film(w, h);
  RenderOptions options;
  options.aovs = {"objectid", "materialid"};
  options.threads = threads;
  renderImage(*integrator, film, options);
  int objectLayer = film.findLayer("objectid"), materialLayer = film.findLayer("materialid");
  return {std::move(scene), std::move(film), objectLayer, materialLayer};
}

struct Box2 {
  int x0 = 1 << 30, y0 = 1 << 30, x1 = -1, y1 = -1;
  void extend(int x, int y) {
    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
  }
};

TEST(KhronosTextureCoordinateTest, EachQuadShowsItsCornerOfTheTexture) {
  // The texture has checker marks in its four corners and is split between four quads, each
  // mapping one quadrant, placed where that quadrant's label says ("Top Left", ...). With uv
  // right (v down the image, u across), each quad shows a checker mark in its outer corner and
  // plain colour in its two neighbouring corners; a flipped u or v moves the mark.
  Render r = renderAmbient("TextureCoordinateTest.glb", 400, 300);
  // Nodes 3, 4, 1, 2: TopLeftObj, TopRightObj, BottomLeftObj, BottomRightObj.
  struct Quad {
    int node;
    bool right, bottom;  // which corner of the screen (and of the image) is outer
    Color factor;
  };
  const Quad quads[] = {{3, false, false, {0.8f, 0.8f, 0}},
                        {4, true, false, {0.8f, 0.08f, 0}},
                        {1, false, true, {0, 0.16f, 0.8f}},
                        {2, true, true, {0, 0.8f, 0}}};
  for (const Quad& q : quads) {
    Box2 box;
    for (int y = 0; y < 300; ++y)
      for (int x = 0; x < 400; ++x)
        if (r.object(x, y) == q.node) box.extend(x, y);
    ASSERT_GT(box.x1 - box.x0, 40) << q.node;
    // The quad is where its label says on screen.
    EXPECT_EQ((box.x0 + box.x1) / 2 > 200, q.right) << q.node;
    EXPECT_EQ((box.y0 + box.y1) / 2 > 150, q.bottom) << q.node;
    // Darkest pixel (relative to the quad's colour) in a corner region of 15% of the box.
    auto darkest = [&](bool right, bool bottom) {
      const int w = (box.x1 - box.x0) * 15 / 100, h = (box.y1 - box.y0) * 15 / 100;
      const int inset = 2;
      int xs = right ? box.x1 - inset - w : box.x0 + inset,
          ys = bottom ? box.y1 - inset - h : box.y0 + inset;
      float d = 1e9f;
      for (int y = ys; y <= ys + h; ++y)
        for (int x = xs; x <= xs + w; ++x)
          if (r.object(x, y) == q.node)
            d = std::min(d, maxComponent(r.at(x, y)) / maxComponent(q.factor));
      return d;
    };
    EXPECT_LT(darkest(q.right, q.bottom), 0.2f) << "outer corner of node " << q.node;
    EXPECT_GT(darkest(!q.right, q.bottom), 0.8f)
        << "horizontal neighbour corner of node " << q.node;
    EXPECT_GT(darkest(q.right, !q.bottom), 0.8f) << "vertical neighbour corner of node " << q.node;
    // The label: one line of text ("Top Left", "Top Right") or two ("Bottom" above "Left"),
    // next to the outer corner. A flipped v would show the mirrored quadrant's label here
    // (the corner marks alone cannot tell: they are mirror-symmetric). Measure the label's
    // height as the span of rows with dark pixels in the band 20%..60% from the outer side
    // edge and 15%..50% from the outer top/bottom edge (clear of the marks and the crosses).
    const int bw = box.x1 - box.x0, bh = box.y1 - box.y0;
    int firstRow = -1, lastRow = -1;
    for (int b = bh * 15 / 100; b <= bh * 50 / 100; ++b) {
      const int y = q.bottom ? box.y1 - b : box.y0 + b;
      for (int a = bw * 20 / 100; a <= bw * 60 / 100; ++a) {
        const int x = q.right ? box.x1 - a : box.x0 + a;
        if (r.object(x, y) == q.node && maxComponent(r.at(x, y)) < 0.3f * maxComponent(q.factor)) {
          if (firstRow < 0) firstRow = b;
          lastRow = b;
        }
      }
    }
    ASSERT_GE(firstRow, 0) << "no label on node " << q.node;
    const float labelHeight = float(lastRow - firstRow + 1) / float(bh);
    if (q.bottom)
      EXPECT_GT(labelHeight, 0.15f) << "two-line label expected on node " << q.node;
    else
      EXPECT_LT(labelHeight, 0.10f) << "one-line label expected on node " << q.node;
    // The quad's middle is the white of the texture times its colour.
    Color mid = r.at((box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2);
    EXPECT_NEAR(mid.x, q.factor.x, 0.02f) << q.node;
    EXPECT_NEAR(mid.y, q.factor.y, 0.02f) << q.node;
    EXPECT_NEAR(mid.z, q.factor.z, 0.02f) << q.node;
  }
}

TEST(KhronosTextureSettingsTest, WrapModesShowGreenChecksAndNoRedCrosses) {
  // Each test cell shows green (a check mark, or a green bar for the clamp tests) when its
  // sampler is honoured and red (a cross, or red bar) when not.
  Render r = renderAmbient("TextureSettingsTest.glb", 400, 300);
  // Materials: 0 mirror T, 1 mirror S, 2 repeat T, 3 clamp T, 5 repeat S, 6 clamp S,
  // 7 double-sided (seen from behind). 8, single-sided, would need back-face culling, which
  // TRay does not do (its red cross shows); 4 and 9 are the background and labels.
  for (int material : {0, 1, 2, 3, 5, 6, 7}) {
    int green = 0, red = 0;
    for (int y = 0; y < 300; ++y)
      for (int x = 0; x < 400; ++x) {
        if (r.material(x, y) != material) continue;
        Color c = r.at(x, y);
        green += c.y > 0.3f && c.x < 0.15f;
        red += c.x > 0.3f && c.y < 0.15f;
      }
    EXPECT_GT(green, 20) << "material " << material;
    EXPECT_EQ(red, 0) << "material " << material;
  }
}

}  // namespace
}  // namespace tray

namespace tray {
namespace {

TEST(KhronosTextureSettingsTest, SameImageForOneAndTwoThreads) {
  // MIP levels are built lazily by whichever thread needs them first: that must not matter.
  Render one = renderAmbient("TextureSettingsTest.glb", 160, 120, 1);
  Render two = renderAmbient("TextureSettingsTest.glb", 160, 120, 2);
  int differing = 0;
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) differing += !(one.at(x, y) == two.at(x, y));
  EXPECT_EQ(differing, 0);
}

}  // namespace
}  // namespace tray

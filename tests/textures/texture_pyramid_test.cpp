// TexturePyramid and the compact texel store: OIIO filters exactly the values it filtered when
// it made the MIP levels itself (automip) from float images, for odd sizes, every glTF filter
// and footprints from magnification down to the 1x1 level; and a TextureImage of 8- or 16-bit
// codes gives, row by row, the floats the loader used to store.
#include "textures/texture_pyramid.h"

#include <OpenImageIO/fmath.h>
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cstring>
#include <random>

#include "tests/textures/random_texture.h"
#include "textures/texture_sampler.h"

namespace tray {
namespace {

bool sameBits(const Color& a, const Color& b) {
  return std::memcmp(&a, &b, sizeof(Color)) == 0;
}

TEST(TexturePyramid, LevelSizesAreOiiosAutomipSizes) {
  const TextureImage im = test::randomFloatImage(37, 5, 1);
  const TexturePyramid p(im);
  // 37x5 -> 18x2 -> 9x1 -> 4x1 -> 2x1 -> 1x1
  ASSERT_EQ(p.levels(), 6);
  EXPECT_EQ(p.width(1), 18);
  EXPECT_EQ(p.height(1), 2);
  EXPECT_EQ(p.width(2), 9);
  EXPECT_EQ(p.height(2), 1);
  EXPECT_EQ(p.width(5), 1);
  EXPECT_EQ(p.height(5), 1);
}

TEST(TexturePyramid, FilteredLookupsMatchOiioAutomipBitForBit) {
  // Odd, tall, wide and power-of-two sizes; levels past kComputed are stored, the others made
  // on demand, so both paths are compared.
  std::vector<TextureImage> images{
      test::randomFloatImage(37, 5, 1), test::randomFloatImage(1, 19, 2),
      test::randomFloatImage(64, 64, 3), test::randomFloatImage(131, 67, 4),
      test::randomFloatImage(300, 200, 5)};
  const TextureSampler ours(images, 0, TextureBackend::kOiio),
      oiio(images, 0, TextureBackend::kOiioAutomip);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uv(-0.5f, 1.5f), logScale(-12.0f, 1.0f);
  const TextureFilter filters[] = {TextureFilter::kNearest,
                                   TextureFilter::kLinear,
                                   TextureFilter::kNearestMipmapNearest,
                                   TextureFilter::kLinearMipmapNearest,
                                   TextureFilter::kNearestMipmapLinear,
                                   TextureFilter::kLinearMipmapLinear};
  size_t compared = 0, differ = 0;
  for (int image = 0; image < int(images.size()); ++image)
    for (TextureFilter f : filters)
      for (int i = 0; i < 400; ++i) {
        TextureRef r;
        r.image = image;
        r.minFilter = f;
        r.wrapS = i % 3 == 0 ? TextureWrap::kClampToEdge : TextureWrap::kRepeat;
        r.wrapT = i % 5 == 0 ? TextureWrap::kMirroredRepeat : TextureWrap::kRepeat;
        const float s = std::exp2(logScale(rng));  // footprint: 1/4096 to 2 in uv
        const UvFootprint fp{{uv(rng), uv(rng)}, {s, 0.3f * s}, {-0.2f * s, 0.7f * s}};
        ++compared;
        differ += !sameBits(ours.sample(r, fp), oiio.sample(r, fp));
      }
  EXPECT_EQ(differ, 0u) << "of " << compared << " lookups";
}

/// The pyramid as OIIO's read_unmipped makes it, written plainly: each whole level from the
/// whole level below (TextureImage::row for level 0), texel by texel with OIIO::floorfrac and
/// OIIO::bilerp, texels outside the finer level 0. The arithmetic TRay's blocks and tiles must
/// repeat bit for bit.
std::vector<std::vector<float>> referenceLevels(const TextureImage& im) {
  int w = im.width, h = im.height;
  std::vector<std::vector<float>> levels(1, std::vector<float>(size_t(w) * size_t(h) * 3));
  for (int y = 0; y < h; ++y) im.row(y, levels[0].data() + size_t(y) * size_t(w) * 3);
  const float zero[3] = {0, 0, 0};
  while (w > 1 || h > 1) {
    const int upW = w, upH = h;
    w = std::max(1, w / 2), h = std::max(1, h / 2);
    const std::vector<float>& up = levels.back();
    std::vector<float> level(size_t(w) * size_t(h) * 3);
    auto at = [&](int x, int y) {
      return x < upW && y < upH ? &up[3 * (size_t(y) * size_t(upW) + size_t(x))] : zero;
    };
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        int x, y;
        const float xf = OIIO::floorfrac((i + 0.5f) / float(w) * upW - 0.5, &x);
        const float yf = OIIO::floorfrac((j + 0.5f) / float(h) * upH - 0.5, &y);
        OIIO::bilerp(at(x, y), at(x + 1, y), at(x, y + 1), at(x + 1, y + 1), xf, yf, 3,
                     &level[3 * (size_t(j) * size_t(w) + size_t(i))]);
      }
    levels.push_back(std::move(level));
  }
  return levels;
}

TEST(TexturePyramid, EveryTexelOfEveryLevelIsTheReferences) {
  // Tiles (texel(), made in any order on many threads) and rows (row(), OIIO's reader) against
  // referenceLevels: floats, 8- and 16-bit codes with 1 to 4 channels, odd, even, non-square,
  // 1xN and Nx1 sizes, several tiles per level with odd sizes at the tile edges.
  std::vector<TextureImage> images{test::randomFloatImage(37, 5, 1),
                                   test::randomFloatImage(1, 19, 2),
                                   test::randomFloatImage(300, 200, 3),
                                   test::randomCodeImage(19, 1, 3, false, 4),
                                   test::randomCodeImage(531, 267, 3, false, 5),
                                   test::randomCodeImage(256, 256, 4, false, 6),
                                   test::randomCodeImage(97, 61, 1, true, 7),
                                   test::randomCodeImage(45, 300, 2, false, 8),
                                   test::randomCodeImage(130, 129, 4, true, 9),
                                   test::randomCodeImage(259, 3, 2, true, 10),
                                   test::randomCodeImage(1, 1, 3, true, 11)};
  for (const TextureImage& im : images) {
    const auto expected = referenceLevels(im);
    const TexturePyramid p(im);
    ASSERT_EQ(p.levels(), int(expected.size())) << im.width << "x" << im.height;
    size_t differ = 0, rowsDiffer = 0;
    // Coarsest first, so that each tiled level's tiles make the finer tiles they read.
    for (int level = p.levels() - 1; level >= 0; --level) {
      const int w = p.width(level), h = p.height(level);
      std::vector<float> tiled(size_t(w) * size_t(h) * 3), row(size_t(w) * 3);
      tbb::parallel_for(0, h, [&](int y) {
        for (int x = w - 1; x >= 0; --x) {
          float scratch[3];
          const float* t = p.texel(level, x, h - 1 - y, scratch);
          std::memcpy(&tiled[3 * (size_t(h - 1 - y) * size_t(w) + size_t(x))], t, 12);
        }
      });
      differ += std::memcmp(tiled.data(), expected[size_t(level)].data(), tiled.size() * 4) != 0;
      for (int y = 0; y < h; ++y) {
        p.row(level, y, row.data());
        rowsDiffer += std::memcmp(row.data(), &expected[size_t(level)][size_t(y) * row.size()],
                                  row.size() * 4) != 0;
      }
    }
    EXPECT_EQ(differ, 0u) << "levels differ, " << im.width << "x" << im.height;
    EXPECT_EQ(rowsDiffer, 0u) << "rows differ, " << im.width << "x" << im.height;
  }
}

TEST(TextureImage, CodeRowsAreTheTableValues) {
  for (int channels : {1, 2, 3, 4})
    for (bool wide : {false, true}) {
      auto codes = std::make_shared<TexelCodes>();
      codes->channels = channels;
      codes->wide = wide;
      const int w = 5, h = 3;
      codes->bytes.resize(size_t(w * h * channels) * (wide ? 2 : 1));
      std::mt19937 rng(uint32_t(channels * 2 + wide));
      for (auto& b : codes->bytes) b = (unsigned char)(rng() & 0xff);
      auto table = std::make_shared<std::vector<float>>(wide ? 65536 : 256);
      for (size_t i = 0; i < table->size(); ++i) (*table)[i] = float(i) * 0.001f + 0.5f;
      TextureImage im;
      im.width = w, im.height = h;
      im.codes = codes;
      im.table = table;
      im.codesAlpha = channels == 2 || channels == 4;
      ASSERT_TRUE(im.valid());
      std::vector<float> row(size_t(w) * 3);
      for (int y = 0; y < h; ++y) {
        im.row(y, row.data());
        for (int x = 0; x < w; ++x)
          for (int c = 0; c < 3; ++c) {
            const size_t k = size_t((y * w + x) * channels + (channels >= 3 ? c : 0));
            EXPECT_EQ(row[size_t(3 * x + c)], (*table)[codes->code(k)]);
          }
        if (im.codesAlpha) {
          EXPECT_EQ(im.alphaAt(size_t(y * w)),
                    float(codes->code(size_t(y * w * channels + channels - 1))) *
                        (1.0f / float(wide ? 65535 : 255)));
        }
      }
    }
}

}  // namespace
}  // namespace tray

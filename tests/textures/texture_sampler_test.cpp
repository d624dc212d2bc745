// TextureSampler: filtering at known uvs of tiny images, the glTF wrap modes and
// filters, the texture memory budget and KHR_texture_transform.
#include "textures/texture_sampler.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tray {
namespace {

/// 2x2 RGB image, texel (x, y) at pixels[3 (2y + x)]: red, green / blue, white.
TextureImage twoByTwo() {
  TextureImage im;
  im.name = "2x2";
  im.width = im.height = 2;
  im.pixels = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  return im;
}

Color texel(const TextureImage& im, int x, int y) {
  const float* p = &im.pixels[3 * (size_t(y) * im.width + x)];
  return {p[0], p[1], p[2]};
}

/// Bilinear interpolation written from its definition (texel centres at (i + 0.5) / size),
/// with clamped texel indices: the reference the filter must reproduce for CLAMP_TO_EDGE.
Color bilinearClamped(const TextureImage& im, float u, float v) {
  float x = u * im.width - 0.5f, y = v * im.height - 0.5f;
  int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  float fx = x - x0, fy = y - y0;
  auto at = [&](int i, int j) {
    return texel(im, std::clamp(i, 0, im.width - 1), std::clamp(j, 0, im.height - 1));
  };
  return (1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) +
         (1 - fx) * fy * at(x0, y0 + 1) + fx * fy * at(x0 + 1, y0 + 1);
}

void expectColor(const Color& got, const Color& want, float tol = 1e-5f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

TextureRef ref(TextureWrap wrap, TextureFilter mag = TextureFilter::kLinear) {
  TextureRef r;
  r.image = 0;
  r.wrapS = r.wrapT = wrap;
  r.magFilter = mag;
  return r;
}

Color at(const TextureSampler& s, const TextureRef& r, float u, float v) {
  return s.sample(r, UvFootprint{{u, v}, {0, 0}, {0, 0}});
}

TEST(TextureSampler, TwoByTwoBilinearAtKnownUvs) {
  std::vector<TextureImage> images{twoByTwo()};
  TextureSampler sampler(images);
  const TextureRef clamp = ref(TextureWrap::kClampToEdge);
  // Texel centres give the texels themselves; the centre of the image their mean.
  expectColor(at(sampler, clamp, 0.25f, 0.25f), {1, 0, 0});
  expectColor(at(sampler, clamp, 0.75f, 0.25f), {0, 1, 0});
  expectColor(at(sampler, clamp, 0.25f, 0.75f), {0, 0, 1});
  expectColor(at(sampler, clamp, 0.5f, 0.5f), {0.5f, 0.5f, 0.5f});
  for (float u : {0.3f, 0.375f, 0.6f, 0.9f})
    for (float v : {0.1f, 0.4f, 0.55f})
      expectColor(at(sampler, clamp, u, v), bilinearClamped(images[0], u, v));
}

TEST(TextureSampler, WrapModes) {
  std::vector<TextureImage> images{twoByTwo()};
  TextureSampler sampler(images);
  const TextureRef repeat = ref(TextureWrap::kRepeat), clamp = ref(TextureWrap::kClampToEdge),
                   mirror = ref(TextureWrap::kMirroredRepeat);
  // The corner (0, 0): clamp sees only texel (0, 0); repeat blends all four (the neighbours
  // across the edges are the far texels).
  expectColor(at(sampler, clamp, 0.0f, 0.0f), {1, 0, 0});
  expectColor(at(sampler, repeat, 0.0f, 0.0f), {0.5f, 0.5f, 0.5f});
  // Repeat has period 1; mirror reflects at 1, so 1.25 reads like 0.75; clamp holds the edge.
  expectColor(at(sampler, repeat, 1.25f, 0.25f), {1, 0, 0});
  expectColor(at(sampler, repeat, -0.75f, 0.25f), {1, 0, 0});
  expectColor(at(sampler, mirror, 1.25f, 0.25f), {0, 1, 0});
  expectColor(at(sampler, mirror, 0.25f, 1.25f), {0, 0, 1});
  expectColor(at(sampler, clamp, 3.0f, 0.25f), {0, 1, 0});
  // Per axis: S repeats, T clamps.
  TextureRef mixed = repeat;
  mixed.wrapT = TextureWrap::kClampToEdge;
  expectColor(at(sampler, mixed, 1.25f, 1.75f), {0, 0, 1});
}

TEST(TextureSampler, NearestMagnificationPicksTheTexel) {
  std::vector<TextureImage> images{twoByTwo()};
  TextureSampler sampler(images);
  const TextureRef nearest = ref(TextureWrap::kClampToEdge, TextureFilter::kNearest);
  expectColor(at(sampler, nearest, 0.45f, 0.05f), {1, 0, 0});
  expectColor(at(sampler, nearest, 0.55f, 0.45f), {0, 1, 0});
  expectColor(at(sampler, nearest, 0.95f, 0.95f), {1, 1, 1});
}

/// 64 x 64 one-texel checker of 0 and 1: any filter wider than a few texels averages to 0.5.
TextureImage checker64() {
  TextureImage im;
  im.name = "checker";
  im.width = im.height = 64;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      float c = (x + y) % 2 ? 1.0f : 0.0f;
      im.pixels.insert(im.pixels.end(), {c, c, c});
    }
  return im;
}

TEST(TextureSampler, MipMappedMinificationAveragesAndLinearDoesNot) {
  std::vector<TextureImage> images{checker64()};
  TextureSampler sampler(images);
  TextureRef r = ref(TextureWrap::kRepeat);
  const float u = (10 + 0.5f) / 64, v = (20 + 0.5f) / 64;  // texel (10, 20): value 0
  // No footprint: the finest level, the texel itself.
  EXPECT_NEAR(at(sampler, r, u, v).x, 0.0f, 1e-6f);
  // A footprint of 16 texels: a coarse MIP level where the checker has averaged out.
  const float d = 16.0f / 64;
  EXPECT_NEAR(sampler.sample(r, {{u, v}, {d, 0}, {0, d}}).x, 0.5f, 0.02f);
  // minFilter LINEAR: no MIP mapping, the finest level however large the footprint (aliasing).
  r.minFilter = TextureFilter::kLinear;
  EXPECT_NEAR(sampler.sample(r, {{u, v}, {d, 0}, {0, d}}).x, 0.0f, 1e-6f);
}

// One filter without MIP levels both ways (the heavy bench scene's LINEAR samplers): the
// footprint can change nothing, so shading skips computing it (footprintMatters) and sample()
// reads the uv alone. Any footprint then gives the no-footprint lookup's bits, through TRay's
// filter and OIIO's (whose no-MIP lookup reads no derivatives either).
TEST(TextureSampler, OneFilterWithoutMipLevelsIgnoresTheFootprint) {
  using F = TextureFilter;
  TextureRef r = ref(TextureWrap::kRepeat);
  EXPECT_TRUE(TextureSampler::footprintMatters(r)) << "glTF's open minFilter: trilinear";
  r.minFilter = F::kLinear;
  EXPECT_FALSE(TextureSampler::footprintMatters(r));
  r.magFilter = r.minFilter = F::kNearest;
  EXPECT_FALSE(TextureSampler::footprintMatters(r));
  r.minFilter = F::kLinear;  // the footprint picks which of the two filters
  EXPECT_TRUE(TextureSampler::footprintMatters(r));
  r.magFilter = r.minFilter = F::kLinearMipmapNearest;
  EXPECT_TRUE(TextureSampler::footprintMatters(r));

  std::vector<TextureImage> images{checker64()};
  const TextureSampler own(images), paged(images, 1e-3);
  ASSERT_FALSE(own.paged());
  ASSERT_TRUE(paged.paged());
  for (F f : {F::kLinear, F::kNearest}) {
    r.magFilter = r.minFilter = f;
    for (float u : {0.1f, 0.37f, 0.8f}) {
      const float v = 1.0f - u, d = 16.0f / 64;
      for (const TextureSampler* s : {&own, &paged}) {
        const Color none = at(*s, r, u, v), wide = s->sample(r, {{u, v}, {d, 0}, {0, d}});
        EXPECT_TRUE(none == wide) << u;
      }
      EXPECT_TRUE(at(own, r, u, v) == at(paged, r, u, v)) << u;
    }
  }
}

/// A size x size image of smooth colours.
TextureImage gradient(int size) {
  TextureImage im;
  im.name = "gradient";
  im.width = im.height = size;
  im.pixels.resize(size_t(size) * size_t(size) * 3);
  for (size_t i = 0; i < im.pixels.size(); ++i) im.pixels[i] = float(i % 997) / 997.0f;
  return im;
}

/// Two passes over the finest level, four lookups in every 64 x 64 tile per pass; returns
/// the tiles OIIO had to read again, and the looked-up values in `values`.
int64_t readTwiceAcrossEveryTile(const TextureSampler& s, int size, std::vector<Color>& values) {
  const TextureRef r = ref(TextureWrap::kClampToEdge);
  for (int pass = 0; pass < 2; ++pass)
    for (int y = 0; y < size; y += 32)
      for (int x = 0; x < size; x += 32)
        values.push_back(at(s, r, (x + 0.5f) / float(size), (y + 0.5f) / float(size)));
  return s.tilesReadAgain();
}

// The budget decides who filters. TRay's own filter never evicts a MIP tile, so it runs when
// every tile it could make fits the budget (the default always does, up to a quarter of RAM);
// under a smaller budget OIIO's cache pages the levels, evicts tiles and makes them again from
// the codes (DamagedHelmet at the former fixed 128 MB: 10x slower). Pixels never change.
TEST(TextureSampler, ASmallBudgetPagesThroughOiioAndTheDefaultKeepsEveryTile) {
  const int size = 2048;  // levels 1-3 as floats: 15.75 MiB; the finest level alone 48 MiB
  std::vector<TextureImage> images{gradient(size)};
  std::vector<Color> small, sized;
  const TextureSampler paged(images, 10);
  EXPECT_TRUE(paged.paged());
  EXPECT_GT(readTwiceAcrossEveryTile(paged, size, small), 0);
  const TextureSampler byScene(images);
  EXPECT_FALSE(byScene.paged());
  EXPECT_GE(byScene.cacheMB(), 16.0);
  EXPECT_EQ(readTwiceAcrossEveryTile(byScene, size, sized), 0);
  EXPECT_EQ(byScene.tilesMade(), 0) << "the finest level is read from the image, not tiled";
  ASSERT_EQ(small.size(), sized.size());
  for (size_t i = 0; i < small.size(); ++i) ASSERT_TRUE(small[i] == sized[i]) << i;
}

TEST(TextureSampler, BudgetIsEveryLevelAsFloatsWithinBounds) {
  EXPECT_EQ(TextureSampler::budgetFor({}), TextureSampler::kMinCacheMB);
  // DamagedHelmet: five 2048^2 images, 48 MiB each as floats, 4/3 with their levels, +10%.
  TextureImage helmetSized;
  helmetSized.width = helmetSized.height = 2048;
  const std::vector<TextureImage> helmet(5, helmetSized);
  EXPECT_EQ(TextureSampler::budgetFor(helmet), std::ceil(1.1 * 4.0 / 3.0 * 48 * 5));
  // TRay's filter makes at most levels 1-3 in tiles: 12 + 3 + 0.75 MiB per image.
  EXPECT_EQ(TextureSampler::tileMBAtMost(helmet), 5 * 15.75);
  // Never more than a quarter of physical memory, never under the minimum.
  TextureImage huge;
  huge.width = huge.height = 1 << 20;
  const double capped = TextureSampler::budgetFor({huge});
  EXPECT_GE(capped, TextureSampler::kMinCacheMB);
  EXPECT_LT(capped, 1.1 * 4.0 / 3.0 * 12.0 * double(1 << 20) * double(1 << 20) / (1 << 20));
}

TEST(TextureTransform, FollowsTheExtensionsExample) {
  // KHR_texture_transform README: offset [0, 1], rotation pi/2, scale 0.5 maps the unit square
  // onto the lower-left quadrant [0, 0.5] x [0.5, 1] of the image (v grows downwards).
  TextureRef r;
  r.offset = {0, 1};
  r.rotation = kPi / 2;
  r.scaleUV = {0.5f, 0.5f};
  auto expectUv = [&](Vec2 in, Vec2 want) {
    Vec2 got = transformUv(r, in);
    EXPECT_NEAR(got.x, want.x, 1e-6f);
    EXPECT_NEAR(got.y, want.y, 1e-6f);
  };
  expectUv({0, 0}, {0, 1});
  expectUv({1, 0}, {0, 0.5f});
  expectUv({0, 1}, {0.5f, 1});
  expectUv({1, 1}, {0.5f, 0.5f});
  // Derivatives see only the linear part.
  Vec2 d = transformUv(r, {1, 0}, true);
  EXPECT_NEAR(d.x, 0.0f, 1e-6f);
  EXPECT_NEAR(d.y, -0.5f, 1e-6f);
}

TEST(TextureSampler, TransformAppliesBeforeLookup) {
  std::vector<TextureImage> images{twoByTwo()};
  TextureSampler sampler(images);
  TextureRef r = ref(TextureWrap::kClampToEdge);
  r.offset = {0.5f, 0.5f};
  // (0.25, 0.25) + offset = (0.75, 0.75): the white texel.
  expectColor(at(sampler, r, 0.25f, 0.25f), {1, 1, 1});
}

}  // namespace
}  // namespace tray

// TRay's texture filter against its reference, OpenImageIO 2.4's TextureSystem over the same
// pyramid: random lookups with every wrap and filter, footprints from none to wider than the
// image, anisotropic ones, uvs far outside [0, 1], texture transforms, odd image shapes (1x1,
// 1xN, Nx1, non-square, non-power-of-two) and every texel store (floats, 8- and 16-bit codes
// with 1 to 4 channels). Tolerance: none. The filter repeats OIIO's float operations in order
// (textures/texture_lookup.cpp), so any difference at all is a bug, and the test says how many.
#include "textures/texture_lookup.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cstring>
#include <random>

#include "tests/textures/random_texture.h"
#include "textures/texture_pyramid.h"
#include "textures/texture_sampler.h"

namespace tray {
namespace {

std::vector<TextureImage> testImages() {
  return {test::randomFloatImage(37, 5, 1),
          test::randomFloatImage(1, 19, 2),
          test::randomFloatImage(19, 1, 3),
          test::randomFloatImage(1, 1, 4),
          test::randomFloatImage(64, 64, 5),
          test::randomFloatImage(131, 67, 6),
          test::randomFloatImage(256, 96, 7),
          test::randomFloatImage(300, 200, 8),
          test::randomCodeImage(97, 61, 3, false, 9),
          test::randomCodeImage(50, 33, 1, true, 10),
          test::randomCodeImage(128, 128, 4, false, 11),
          test::randomCodeImage(45, 300, 2, false, 12)};
}

bool sameBits(const Color& a, const Color& b) {
  return std::memcmp(&a, &b, sizeof(Color)) == 0;
}

/// A random lookup: uvs mostly near [0, 1], some thousands or 10^5 away; footprints of 2^-24
/// to 2^3 image widths (or none), the two axes of independent lengths and directions.
struct RandomLookups {
  std::mt19937 rng{2024};
  std::uniform_real_distribution<float> unit{0.0f, 1.0f};

  float uvCoordinate() {
    const float pick = unit(rng);
    if (pick < 0.7f) return -2.0f + 5.0f * unit(rng);
    if (pick < 0.9f) return -1000.0f + 2000.0f * unit(rng);
    return -1e5f + 2e5f * unit(rng);
  }
  Vec2 derivative() {
    if (unit(rng) < 0.05f) return {0, 0};
    const float length = std::exp2(-24.0f + 27.0f * unit(rng)), angle = 2 * kPi * unit(rng);
    return {length * std::cos(angle), length * std::sin(angle)};
  }
  TextureRef ref(int image) {
    static const TextureFilter filters[] = {TextureFilter::kNearest,
                                            TextureFilter::kLinear,
                                            TextureFilter::kNearestMipmapNearest,
                                            TextureFilter::kLinearMipmapNearest,
                                            TextureFilter::kNearestMipmapLinear,
                                            TextureFilter::kLinearMipmapLinear};
    static const TextureWrap wraps[] = {TextureWrap::kRepeat, TextureWrap::kClampToEdge,
                                        TextureWrap::kMirroredRepeat};
    TextureRef r;
    r.image = image;
    r.wrapS = wraps[rng() % 3];
    r.wrapT = wraps[rng() % 3];
    r.magFilter = rng() % 2 ? TextureFilter::kLinear : TextureFilter::kNearest;
    r.minFilter = filters[rng() % 6];
    if (rng() % 3 == 0) {  // KHR_texture_transform
      r.offset = {unit(rng) * 4 - 2, unit(rng) * 4 - 2};
      r.rotation = unit(rng) * 2 * kPi;
      r.scaleUV = {std::exp2(unit(rng) * 8 - 4), std::exp2(unit(rng) * 8 - 4)};
    }
    return r;
  }
};

TEST(TextureLookup, RandomLookupsEqualOiiosBitForBit) {
  const std::vector<TextureImage> images = testImages();
  const TextureSampler tray(images, 0, TextureBackend::kTray),
      oiio(images, 0, TextureBackend::kOiio);
  ASSERT_FALSE(tray.paged());
  ASSERT_TRUE(oiio.paged());
  RandomLookups random;
  size_t compared = 0, differ = 0;
  for (int image = 0; image < int(images.size()); ++image)
    for (int i = 0; i < 4000; ++i) {
      const TextureRef r = random.ref(image);
      const UvFootprint f{
          {random.uvCoordinate(), random.uvCoordinate()}, random.derivative(), random.derivative()};
      const Color a = tray.sample(r, f), b = oiio.sample(r, f);
      ++compared;
      if (!sameBits(a, b) && ++differ <= 5)
        ADD_FAILURE() << "image " << image << " uv " << f.uv.x << "," << f.uv.y << " dx " << f.dx.x
                      << "," << f.dx.y << " dy " << f.dy.x << "," << f.dy.y << ": " << a.x << " "
                      << a.y << " " << a.z << " against OIIO's " << b.x << " " << b.y << " " << b.z;
    }
  EXPECT_EQ(differ, 0u) << "of " << compared << " lookups";
}

TEST(TextureLookup, AtTexelCentresEveryLevelGivesItsTexels) {
  // A footprint that selects exactly one MIP level, at its texel centres: the pyramid's texels,
  // level by level.
  const TextureImage im = test::randomFloatImage(40, 24, 3);
  const TexturePyramid p(im);
  for (int level = 0; level < p.levels(); ++level) {
    const int w = p.width(level), h = p.height(level);
    // compute_miplevels: a filter width of exactly 1 / min(w, h) gives this level alone.
    const float width = 1.0f / float(std::min(w, h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        TextureQuery q;
        q.s = (x + 0.5f) / float(w), q.t = (y + 0.5f) / float(h);
        q.dsdx = width, q.dtdy = width;
        q.wrapS = q.wrapT = TextureWrap::kClampToEdge;
        float scratch[3];
        const float* want = p.texel(level, x, y, scratch);
        const Color got = lookupTexture(p, q);
        ASSERT_EQ(got.x, want[0]) << level << " " << x << " " << y;
        ASSERT_EQ(got.z, want[2]) << level << " " << x << " " << y;
      }
  }
}

TEST(TextureLookup, EveryTileMadeTakesTheBytesThatBoundTheBudget) {
  // tileBytesAtMost is what decides between TRay's filter and OIIO's paged cache: reading every
  // texel of every tiled level makes tiles of exactly that many bytes, and no more.
  for (auto [w, h] : {std::pair{300, 200}, std::pair{1, 19}, std::pair{131, 67}}) {
    const TextureImage im = test::randomFloatImage(w, h, 5);
    const TexturePyramid p(im);
    float scratch[3];
    for (int level = 1; level <= TexturePyramid::kComputed && level < p.levels(); ++level)
      for (int y = 0; y < p.height(level); ++y)
        for (int x = 0; x < p.width(level); ++x) p.texel(level, x, y, scratch);
    EXPECT_EQ(p.tileBytes(), TexturePyramid::tileBytesAtMost(w, h)) << w << "x" << h;
    EXPECT_GT(p.tileBytes(), 0u);
  }
}

TEST(TextureLookup, TilesAreMadeOnceAndAnyThreadCountGivesTheSameValues) {
  const std::vector<TextureImage> images{test::randomFloatImage(700, 500, 9)};
  // Footprints of 2 to 8 texels: levels 1 to 3, the ones made in tiles on first use.
  std::vector<UvFootprint> lookups;
  RandomLookups random;
  for (int i = 0; i < 20000; ++i) {
    const float d = (2.0f + 6.0f * random.unit(random.rng)) / 700.0f;
    lookups.push_back({{random.unit(random.rng), random.unit(random.rng)}, {d, 0}, {0, d}});
  }
  TextureRef r;
  r.image = 0;
  const TextureSampler serial(images, 0, TextureBackend::kTray);
  std::vector<Color> one(lookups.size()), many(lookups.size());
  for (size_t i = 0; i < lookups.size(); ++i) one[i] = serial.sample(r, lookups[i]);
  const int64_t made = serial.tilesMade();
  EXPECT_GT(made, 0);
  for (size_t i = 0; i < lookups.size(); ++i) serial.sample(r, lookups[i]);
  EXPECT_EQ(serial.tilesMade(), made) << "a second pass made tiles again";
  // Level 1 (350x250: 6x4 tiles), 2 (175x125: 3x2) and 3 (87x62: 2x1) have 32 tiles.
  EXPECT_LE(made, 32);
  const TextureSampler parallel(images, 0, TextureBackend::kTray);  // fresh tiles, racing threads
  tbb::parallel_for(size_t(0), lookups.size(),
                    [&](size_t i) { many[i] = parallel.sample(r, lookups[i]); });
  for (size_t i = 0; i < lookups.size(); ++i) ASSERT_TRUE(sameBits(one[i], many[i])) << i;
}

}  // namespace
}  // namespace tray

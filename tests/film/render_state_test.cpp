// RenderState survives an EXR round trip bit for bit: every double of the sums, including ones
// whose 32-bit words read as float NaNs, infinities or denormals, and the done flags.
#include "film/render_state.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <random>

#include "io/image_input.h"
#include "io/image_output.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

double fromBits(uint64_t bits) {
  double d;
  std::memcpy(&d, &bits, 8);
  return d;
}

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, 8) == 0;
}

TEST(RenderState, RoundTripsThroughExrBitForBit) {
  const int w = 7, h = 5;
  RenderState state = RenderState::empty(size_t(w) * h);
  std::mt19937_64 rng(3);
  // Words that as floats are a signalling NaN, a quiet NaN, +inf, a denormal, -0.
  const uint32_t special[] = {0x7f800001u, 0x7fc00000u, 0x7f800000u, 0x00000001u, 0x80000000u};
  for (size_t p = 0; p < state.sums.size(); ++p) {
    PixelSums& s = state.sums[p];
    double* v[] = {&s.rgb[0], &s.rgb[1], &s.rgb[2], &s.alpha, &s.weight};
    for (int k = 0; k < 5; ++k) {
      const uint64_t lo = (p + k) % 3 == 0 ? special[(p + k) % 5] : uint32_t(rng());
      *v[k] = fromBits(uint64_t(0x3fd55555u + uint32_t(p * 5 + k)) << 32 | lo);
    }
    state.done[p] = p % 3 != 1;
  }
  Film film(w, h);
  storeState(state, film);
  const std::string path = (test::testDir() / "render_state.exr").string();
  writeImage(film, path);  // default options: half beauty; the state layer stays float
  const RenderState back = loadState(readExr(path).film);
  ASSERT_EQ(back.sums.size(), state.sums.size());
  for (size_t p = 0; p < state.sums.size(); ++p) {
    const PixelSums &a = state.sums[p], &b = back.sums[p];
    EXPECT_TRUE(sameBits(a.rgb[0], b.rgb[0]) && sameBits(a.rgb[1], b.rgb[1]) &&
                sameBits(a.rgb[2], b.rgb[2]) && sameBits(a.alpha, b.alpha) &&
                sameBits(a.weight, b.weight))
        << "pixel " << p;
    EXPECT_EQ(back.done[p], state.done[p]);
  }
  EXPECT_EQ(back.pixelsDone(), state.pixelsDone());
}

/// The message loadState throws for `film`, or "" when it loads.
std::string loadError(const Film& film) {
  try {
    loadState(film);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(RenderState, DamagedWordsAreRefusedNamingThePixel) {
  RenderState state = RenderState::empty(6);
  for (PixelSums& s : state.sums) s.rgb[0] = 2.5, s.alpha = 1, s.weight = 1;
  state.done.assign(6, 1);
  Film film(3, 2);
  storeState(state, film);
  EXPECT_EQ(loadError(film), "");
  const int layer = film.findLayer(kStateLayer);
  // A float NaN written into a sum's high word: as a double, about 2^1020 (finite).
  float* px = film.pixel(layer, 1, 1);
  const float saved = px[0];
  px[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(loadError(film).find("pixel (1, 1) holds sums that no render makes"),
            std::string::npos)
      << loadError(film);
  px[0] = saved;
  px[10] = 0.5f;  // done
  EXPECT_NE(loadError(film).find("pixel (1, 1) holds done 0.5, neither 0 nor 1"),
            std::string::npos)
      << loadError(film);
  // What a render can make is kept: a negative weight (Mitchell's lobes), -0, a large sum.
  const float words[11] = {};
  EXPECT_NO_THROW(checkedSums(words));
  PixelSums big;
  big.rgb[1] = 1e45, big.weight = -3;
  RenderState one = RenderState::empty(1);
  one.sums[0] = big;
  Film single(1, 1);
  storeState(one, single);
  EXPECT_EQ(loadError(single), "");
}

TEST(RenderState, FilmWithoutStateIsAnError) {
  EXPECT_THROW(loadState(Film(2, 2)), Error);
}

TEST(PixelSums, AddedRangesGiveTheMean) {
  PixelSums a, b;
  a.rgb[0] = 1.5, a.alpha = 1, a.weight = 2;
  b.rgb[0] = 4.5, b.alpha = 0, b.weight = 2;
  a += b;
  EXPECT_FLOAT_EQ(a.radiance().x, 1.5f);
  EXPECT_FLOAT_EQ(a.coverage(), 0.25f);
  EXPECT_EQ(PixelSums().radiance().x, 0.0f);  // no samples: black, not NaN
}

}  // namespace
}  // namespace tray

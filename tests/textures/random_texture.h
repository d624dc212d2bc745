#pragma once
// Textures of independent uniform random values (linear floats, or codes with a table), for the
// texture filter's and pyramid's tests.
#include <cmath>
#include <memory>
#include <random>
#include <string>

#include "core/texture_image.h"

namespace tray::test {

/// w x h float RGB texels, uniform in [0, 1), reproducible from `seed`.
inline TextureImage randomFloatImage(int w, int h, uint32_t seed) {
  TextureImage im;
  im.name = std::to_string(w) + "x" + std::to_string(h);
  im.width = w, im.height = h;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  im.pixels.resize(size_t(w) * size_t(h) * 3);
  for (float& p : im.pixels) p = u(rng);
  return im;
}

/// Random codes as the glTF loader keeps them, with an sRGB-like table (any increasing table
/// will do).
inline TextureImage randomCodeImage(int w, int h, int channels, bool wide, uint32_t seed) {
  auto codes = std::make_shared<TexelCodes>();
  codes->channels = channels;
  codes->wide = wide;
  codes->bytes.resize(size_t(w) * size_t(h) * size_t(channels) * (wide ? 2 : 1));
  std::mt19937 rng(seed);
  for (auto& b : codes->bytes) b = (unsigned char)(rng() & 0xff);
  auto table = std::make_shared<std::vector<float>>(wide ? 65536 : 256);
  for (size_t i = 0; i < table->size(); ++i)
    (*table)[i] = std::pow(float(i) / float(table->size() - 1), 2.2f);
  TextureImage im;
  im.name = "codes";
  im.width = w, im.height = h;
  im.codes = codes;
  im.table = table;
  im.codesAlpha = channels == 2 || channels == 4;
  return im;
}

}  // namespace tray::test

#pragma once
// A texture of independent uniform random linear values, for the texture filter's tests.
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

}  // namespace tray::test

#pragma once
// Random small boxes in a flat 10 x 10 x 1 slab, for BVH builder and layout tests.
#include <random>
#include <vector>

#include "core/bounds.h"

namespace tray::test {

inline std::vector<Bounds3> randomBoxes(uint32_t seed, int n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Bounds3> boxes(n);
  for (auto& b : boxes) {
    Vec3 c{10 * u(rng), 10 * u(rng), u(rng)};
    Vec3 h = 0.05f * Vec3(u(rng), u(rng), u(rng));
    b = {c - h, c + h};
  }
  return boxes;
}

}  // namespace tray::test

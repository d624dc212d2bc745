#include "core/pixel_sampler.h"

#include <cmath>

#include "core/error.h"

namespace tray {

const std::vector<std::string>& PixelSampler::names() {
  static const std::vector<std::string> n = {"auto", "center", "corners",
                                             "grid", "jitter", "sequence"};
  return n;
}

const OptionSpec& PixelSampler::option() {
  static const OptionSpec spec =
      choiceOption("pixel-sampler", "auto", names(), "where samples go in a pixel");
  return spec;
}

PixelSampler::Pattern PixelSampler::parse(const std::string& name, int spp,
                                          bool stratifiedSequence) {
  if (name == "auto") {
    if (spp <= 1) return Pattern::kCenter;
    // Sobol' positions beat jitter's (stratum i for sample i, random within): the net is also
    // stratified in 1 x spp, 2 x spp/2, ... cells. Cornell box, 64 spp, 4 seeds: mean RMSE
    // 0.01023 against 0.01053 (MSE -6%).
    const bool powerOfTwo = (spp & (spp - 1)) == 0;
    return stratifiedSequence && powerOfTwo ? Pattern::kSequence : Pattern::kJitter;
  }
  if (name == "center") return Pattern::kCenter;
  if (name == "corners") return Pattern::kCorners;
  if (name == "grid") return Pattern::kGrid;
  if (name == "jitter") return Pattern::kJitter;
  if (name == "sequence") return Pattern::kSequence;
  throw Error("unknown pixel sampler '" + name +
              "' (known: auto, center, corners, grid, jitter, sequence)");
}

PixelSampler::PixelSampler(Pattern pattern, int spp, float radius)
    : pattern_(pattern), radius_(radius) {
  spp = std::max(1, spp);
  strata_ = std::max(1, int(std::sqrt(double(spp))));
  while ((strata_ + 1) * (strata_ + 1) <= spp) ++strata_;  // guard sqrt rounding
  switch (pattern) {
    case Pattern::kCenter:
      count_ = 1;
      break;
    case Pattern::kCorners:
      count_ = 4;
      break;
    case Pattern::kGrid:
      count_ = strata_ * strata_;
      break;
    case Pattern::kJitter:
    case Pattern::kSequence:
      count_ = spp;
      break;
  }
}

Vec2 PixelSampler::offset(int i, const Vec2& u) const {
  switch (pattern_) {
    case Pattern::kCenter:
      return {0, 0};
    case Pattern::kCorners:
      return {(i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f};
    case Pattern::kSequence:
      return {(2 * u.x - 1) * radius_, (2 * u.y - 1) * radius_};
    case Pattern::kGrid:
    case Pattern::kJitter: {
      Vec2 s;  // position in [0,1)^2 of the support
      if (pattern_ == Pattern::kJitter && i >= strata_ * strata_) {
        s = u;
      } else {
        Vec2 d = pattern_ == Pattern::kGrid ? Vec2{0.5f, 0.5f} : u;
        s = {(float(i % strata_) + d.x) / float(strata_),
             (float(i / strata_) + d.y) / float(strata_)};
      }
      return {(2 * s.x - 1) * radius_, (2 * s.y - 1) * radius_};
    }
  }
  return {0, 0};
}

}  // namespace tray

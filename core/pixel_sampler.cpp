#include "core/pixel_sampler.h"

#include <cmath>

#include "core/error.h"
#include "core/pixel_sampler_lanes.h"

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

PixelSampler::Pattern PixelSampler::parse(const std::string& name, int spp, bool stratifiedSequence,
                                          bool anyPrefix) {
  if (anyPrefix && (name == "grid" || name == "jitter" || name == "corners"))
    throw Error("--pixel-sampler " + name +
                " puts sample i in stratum i: a pixel that stops early (--noise-threshold, "
                "--time-limit) would see only part of itself; use sequence (auto's choice)");
  if (name == "auto") {
    if (spp <= 1) return Pattern::kCenter;
    if (anyPrefix) return Pattern::kSequence;  // every prefix of the sequence spreads out
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
  return pixelOffset<float>(*this, i, u);  // the SIMD camera kernel's text too
}

}  // namespace tray

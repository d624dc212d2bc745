#include "core/filter.h"

#include <cmath>

#include "core/error.h"

namespace tray {
namespace {

float gaussian(float x, float sigma) {
  return std::exp(-x * x / (2 * sigma * sigma));
}

// Mitchell & Netravali (1988), eq. 8, on |x| in [0, 2]; integrates to 1 over [-2, 2].
float mitchell1D(float x, float B, float C) {
  x = std::abs(x);
  if (x < 1)
    return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) / 6;
  if (x < 2)
    return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x +
            (8 * B + 24 * C)) /
           6;
  return 0;
}

}  // namespace

const std::vector<std::string>& Filter::names() {
  static const std::vector<std::string> n = {"box", "tent", "gaussian", "mitchell"};
  return n;
}

const OptionSpec& Filter::option() {
  static const OptionSpec spec =
      choiceOption("filter", "box", names(), "reconstruction filter");
  return spec;
}

Filter Filter::make(const std::string& name) {
  const auto& n = names();
  for (size_t i = 0; i < n.size(); ++i)
    if (name == n[i]) return Filter(Kind(i));
  throw Error("unknown filter '" + name + "' (known: box, tent, gaussian, mitchell)");
}

Filter::Filter(Kind kind) : kind_(kind) {
  switch (kind) {
    case Kind::kBox:
      radius_ = kBoxRadius;
      break;
    case Kind::kTent:
      radius_ = 1.0f;
      break;
    case Kind::kGaussian:
      radius_ = 1.5f;
      break;
    case Kind::kMitchell:
      radius_ = 2.0f;
      break;
  }
}

float Filter::evaluate1D(float x) const {
  // The box includes its boundary so that the seed's corner rays (offset +-0.5) count.
  if (std::abs(x) > radius_) return 0;
  switch (kind_) {
    case Kind::kBox:
      return 1;
    case Kind::kTent:
      return 1 - std::abs(x) / radius_;
    case Kind::kGaussian:
      // Shifted down so it reaches 0 at the radius instead of being cut off (pbrt-v4 8.8.4).
      return std::max(0.0f, gaussian(x, kGaussianSigma) - gaussian(radius_, kGaussianSigma));
    case Kind::kMitchell:
      return mitchell1D(x * 2 / radius_, 1.0f / 3, 1.0f / 3);
  }
  return 0;
}

}  // namespace tray

#pragma once
// Pixel reconstruction filters: how much a sample at an offset from a pixel's centre counts
// towards that pixel (pbrt-v4, section 8.8; Mitchell & Netravali 1988).
#include <cmath>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/options.h"

namespace tray {

/// A separable filter f(x, y) = f1(x) f1(y) with support [-radius, radius]^2, in pixels.
/// Values need not integrate to 1: the pixel estimate divides by the sum of the weights.
class Filter {
 public:
  enum class Kind { kBox, kTent, kGaussian, kMitchell };
  /// box (radius 0.5), tent (1), gaussian (1.5, sigma 0.5), mitchell (2, B = C = 1/3);
  /// throws tray::Error naming the choices for an unknown name.
  static Filter make(const std::string& name);
  static const std::vector<std::string>& names();
  /// --filter: declared here, beside the filters it names.
  static const OptionSpec& option();
  explicit Filter(Kind kind);

  Kind kind() const { return kind_; }
  float radius() const { return radius_; }
  /// The 1D profile at offset x (0 outside the support; Mitchell is negative in its lobes).
  float evaluate1D(float x) const;
  /// The weight of a sample at `offset` from the pixel centre. The box (the default) inline:
  /// evaluate1D's numbers (1 x 1, or a 0 factor) without its two calls per sample.
  float evaluate(const Vec2& offset) const {
    if (kind_ == Kind::kBox)
      return !(std::abs(offset.x) > kBoxRadius) && !(std::abs(offset.y) > kBoxRadius) ? 1.0f : 0.0f;
    return evaluate1D(offset.x) * evaluate1D(offset.y);
  }

  static constexpr float kGaussianSigma = 0.5f;
  static constexpr float kBoxRadius = 0.5f;

 private:
  Kind kind_;
  float radius_;
};

}  // namespace tray

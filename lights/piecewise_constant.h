#pragma once
// Piecewise-constant distributions in 1D and 2D (pbrt-v4 A.4.1 PiecewiseConstant1D and A.5.2
// PiecewiseConstant2D): a tabulated non-negative function over [0,1) or [0,1)^2, sampled by
// inverting its CDF, so that samples are proportional to the function. The image environment
// light samples its map with the 2D one (marginal over rows, conditional within a row).
#include <cstddef>
#include <vector>

#include "core/math.h"

namespace tray {

class PiecewiseConstant1D {
 public:
  PiecewiseConstant1D() = default;
  /// f: n >= 1 values, finite and >= 0. An all-zero f samples uniformly (pbrt does the same).
  explicit PiecewiseConstant1D(const float* f, size_t n);
  size_t size() const { return func_.size(); }
  /// The integral of f over [0,1) (the mean of the values), before the all-zero fallback.
  float integral() const { return integral_; }
  /// x in [0,1) distributed as f; pdf receives its density (f(x) / integral), offset its cell.
  float sample(float u, float& pdf, size_t& offset) const;
  /// The density at x in [0,1).
  float pdf(float x) const;

 private:
  std::vector<float> func_, cdf_;  ///< cdf_: n + 1 values, 0 .. 1
  float integral_ = 0;
};

class PiecewiseConstant2D {
 public:
  PiecewiseConstant2D() = default;
  /// f: nu x nv values, row-major (f[v * nu + u]), finite and >= 0.
  PiecewiseConstant2D(const std::vector<float>& f, size_t nu, size_t nv);
  /// (u, v) in [0,1)^2 distributed as f; pdf receives the density over [0,1)^2.
  Vec2 sample(Vec2 u, float& pdf) const;
  /// The density at (u, v) in [0,1)^2 (0 outside).
  float pdf(Vec2 p) const;
  /// The integral of f over [0,1)^2.
  float integral() const { return marginal_.integral(); }

 private:
  std::vector<PiecewiseConstant1D> conditional_;  ///< per row v: the distribution over u
  PiecewiseConstant1D marginal_;                  ///< over v: each row's integral
};

}  // namespace tray

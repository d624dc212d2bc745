#include "lights/piecewise_constant.h"

#include <algorithm>
#include <cmath>

namespace tray {

PiecewiseConstant1D::PiecewiseConstant1D(const float* f, size_t n) : func_(f, f + n) {
  cdf_.resize(n + 1);
  // Summed in double: a 16384-wide row of tiny values next to a sun loses nothing.
  double sum = 0;
  cdf_[0] = 0;
  for (size_t i = 0; i < n; ++i) {
    sum += double(func_[i]);
    cdf_[i + 1] = float(sum);
  }
  integral_ = float(sum / double(n));
  if (sum == 0) {
    for (size_t i = 1; i <= n; ++i) cdf_[i] = float(double(i) / double(n));
  } else {
    for (size_t i = 1; i <= n; ++i) cdf_[i] = float(double(cdf_[i]) / sum);
  }
  cdf_[n] = 1.0f;
}

float PiecewiseConstant1D::sample(float u, float& pdf, size_t& offset) const {
  // The last cell whose CDF start is <= u; cells of zero width (f = 0) are never chosen,
  // because upper_bound skips every equal CDF value.
  const size_t n = func_.size();
  offset = size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin());
  offset = std::min(offset == 0 ? 0 : offset - 1, n - 1);
  const float width = cdf_[offset + 1] - cdf_[offset];
  float du = u - cdf_[offset];
  if (width > 0) du /= width;
  pdf = integral_ > 0 ? func_[offset] / integral_ : 1.0f;
  // Just below 1: x stays in [0,1), in its cell.
  const float x = (float(offset) + std::clamp(du, 0.0f, 1.0f)) / float(n);
  return std::min(x, std::nextafter(float(offset + 1) / float(n), 0.0f));
}

float PiecewiseConstant1D::pdf(float x) const {
  if (!(x >= 0 && x < 1) || func_.empty()) return 0.0f;
  const size_t i = std::min(size_t(x * float(func_.size())), func_.size() - 1);
  return integral_ > 0 ? func_[i] / integral_ : 1.0f;
}

PiecewiseConstant2D::PiecewiseConstant2D(const std::vector<float>& f, size_t nu, size_t nv) {
  conditional_.reserve(nv);
  std::vector<float> rows(nv);
  for (size_t v = 0; v < nv; ++v) {
    conditional_.emplace_back(&f[v * nu], nu);
    rows[v] = conditional_.back().integral();
  }
  marginal_ = PiecewiseConstant1D(rows.data(), nv);
}

Vec2 PiecewiseConstant2D::sample(Vec2 u, float& pdf) const {
  float pdfV, pdfU;
  size_t row, column;
  const float v = marginal_.sample(u.y, pdfV, row);
  const float x = conditional_[row].sample(u.x, pdfU, column);
  pdf = pdfU * pdfV;
  return {x, v};
}

float PiecewiseConstant2D::pdf(Vec2 p) const {
  if (!(p.y >= 0 && p.y < 1) || conditional_.empty()) return 0.0f;
  const size_t row = std::min(size_t(p.y * float(conditional_.size())), conditional_.size() - 1);
  return marginal_.pdf(p.y) * conditional_[row].pdf(p.x);
}

}  // namespace tray

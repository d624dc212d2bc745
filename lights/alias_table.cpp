#include "lights/alias_table.h"

#include <algorithm>

namespace tray {

AliasTable::AliasTable(const std::vector<float>& weights) {
  double sum = 0;
  for (float w : weights) sum += std::max(0.0f, w);
  if (!(sum > 0)) return;
  const size_t n = weights.size();
  bins_.resize(n);
  // Scaled probabilities p_i n: "small" ones (< 1) borrow the rest of their bin from a "large".
  std::vector<double> scaled(n);
  std::vector<uint32_t> small, large;
  for (size_t i = 0; i < n; ++i) {
    bins_[i].pmf = float(std::max(0.0f, weights[i]) / sum);
    scaled[i] = std::max(0.0f, weights[i]) / sum * double(n);
    (scaled[i] < 1.0 ? small : large).push_back(uint32_t(i));
  }
  while (!small.empty() && !large.empty()) {
    uint32_t s = small.back(), l = large.back();
    small.pop_back();
    bins_[s].threshold = float(scaled[s]);
    bins_[s].alias = l;
    scaled[l] -= 1.0 - scaled[s];
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // Leftovers are 1 up to rounding.
  for (uint32_t i : small) bins_[i].threshold = 1.0f, bins_[i].alias = i;
  for (uint32_t i : large) bins_[i].threshold = 1.0f, bins_[i].alias = i;
}

uint32_t AliasTable::sample(float u, float& pmf) const {
  const float scaled = u * float(bins_.size());
  uint32_t i = std::min(uint32_t(scaled), uint32_t(bins_.size() - 1));
  float rest = scaled - float(i);
  uint32_t chosen = rest < bins_[i].threshold ? i : bins_[i].alias;
  pmf = bins_[chosen].pmf;
  return chosen;
}

}  // namespace tray

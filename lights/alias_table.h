#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tray {

/// Walker's alias method with Vose's O(n) construction (Vose 1991, "A Linear Algorithm for
/// Generating Random Numbers with a Given Distribution"): picks index i with probability
/// w_i / sum(w) in O(1) from one uniform number.
class AliasTable {
 public:
  AliasTable() = default;
  /// Weights must be finite and >= 0; all-zero (or empty) gives a table that samples nothing.
  explicit AliasTable(const std::vector<float>& weights);
  bool empty() const { return bins_.empty(); }
  size_t size() const { return bins_.size(); }
  /// Index for u in [0,1); pmf receives its probability.
  uint32_t sample(float u, float& pmf) const;
  float pmf(uint32_t i) const { return i < bins_.size() ? bins_[i].pmf : 0.0f; }

 private:
  struct Bin {
    float threshold = 1;  ///< keep i when the remapped u is below this, else take alias
    uint32_t alias = 0;
    float pmf = 0;
  };
  std::vector<Bin> bins_;
};

}  // namespace tray

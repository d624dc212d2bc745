#pragma once
#include "lights/alias_table.h"
#include "lights/light_sampler.h"

namespace tray {

/// Lights in proportion to their power, the same for every receiver (pbrt-v4 12.6.3's
/// PowerLightSampler): an alias table, O(1) per choice. A sun beside a bright environment or
/// one lamp among thousands far away are chosen as often wherever the receiver is.
class PowerLightSampler final : public LightSampler {
 public:
  explicit PowerLightSampler(const std::vector<float>& power) : table_(power) {}
  int sample(const LightSampleContext&, float u, float& pmf) const override {
    if (table_.empty()) return pmf = 0, -1;
    return int(table_.sample(u, pmf));
  }
  float pmf(const LightSampleContext&, int light) const override {
    return light < 0 ? 0.0f : table_.pmf(uint32_t(light));
  }

 private:
  AliasTable table_;
};

}  // namespace tray

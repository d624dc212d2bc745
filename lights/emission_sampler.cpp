#include "lights/emission_sampler.h"

#include <cmath>

namespace tray {

EmissionSampler::EmissionSampler(const LightSet& lights) : lights_(lights) {
  std::vector<float> power(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    const float p = lights.light(i).power();
    power[i] = std::isfinite(p) && p > 0 ? p : 0.0f;
  }
  table_ = AliasTable(power);
}

EmittedRay EmissionSampler::sample(float uLight, Vec2 u1, Vec2 u2) const {
  EmittedRay e;
  if (table_.empty()) return e;
  e.light = int(table_.sample(uLight, e.pmf));
  if (!(e.pmf > 0)) return e.light = -1, e;
  e.le = lights_.light(size_t(e.light)).sampleLe(u1, u2, lights_.world());
  return e;
}

}  // namespace tray

#pragma once
// Choosing where light paths start: a light in proportion to its power, then a ray leaving
// it (Light::sampleLe). Shared by the estimators that trace from the lights (photon mapping,
// bidirectional path tracing); `path` never builds one.
#include "core/light.h"
#include "lights/alias_table.h"
#include "lights/light_set.h"

namespace tray {

/// One emitted ray and where it came from.
struct EmittedRay {
  LightLeSample le;
  int light = -1;  ///< LightSet index; -1: none (no light has power)
  float pmf = 0;   ///< the probability of choosing that light
  bool valid() const { return light >= 0 && pmf > 0 && le.valid(); }
};

/// Lights chosen by power (Light::power), whatever chooser the LightSet uses for next-event
/// estimation: an emitted path has no receiving point to weigh lights by. The power estimates
/// of infinite lights use the world's radius, as the light set's do.
class EmissionSampler {
 public:
  explicit EmissionSampler(const LightSet& lights);
  /// A light chosen with uLight, a ray leaving it with u1 (origin) and u2 (direction).
  EmittedRay sample(float uLight, Vec2 u1, Vec2 u2) const;
  /// The probability that sample() chooses light i.
  float pmf(int i) const { return i < 0 ? 0.0f : table_.pmf(uint32_t(i)); }
  /// Light i's sampleLe densities for a ray leaving it at p (normal n) in direction w.
  LightLePdf pdfLe(int i, const Vec3& p, const Vec3& n, const Vec3& w) const {
    return lights_.light(size_t(i)).pdfLe(p, n, w, lights_.world());
  }
  const LightSet& lights() const { return lights_; }

 private:
  const LightSet& lights_;
  AliasTable table_;
};

}  // namespace tray

#pragma once
// Choosing one light for next-event estimation (pbrt-v4 12.6's LightSampler). LightSet owns
// one; `--light-sampler` (integrators/path.cpp) says which.
#include <memory>
#include <string>
#include <vector>

#include "core/light.h"
#include "core/light_bounds.h"

namespace tray {

class LightSampler {
 public:
  virtual ~LightSampler() = default;
  /// The index of a light chosen for a receiver at ctx with u in [0,1), and its probability
  /// in pmf; -1 (pmf 0) when no light can contribute there.
  virtual int sample(const LightSampleContext& ctx, float u, float& pmf) const = 0;
  /// The probability that sample(ctx, .) returns `light`: bit for bit the pmf sample() gives,
  /// so MIS weights a light found by BSDF sampling as next-event estimation would have.
  virtual float pmf(const LightSampleContext& ctx, int light) const = 0;
};

enum class LightSamplerKind { kPower, kBvh };

/// "power" or "bvh" (the choices of --light-sampler); throws tray::Error otherwise.
LightSamplerKind lightSamplerKind(const std::string& name);

/// kPower: in proportion to power, whatever the receiver (an alias table; pbrt-v4's
/// PowerLightSampler). kBvh: by estimated contribution at the receiver (BvhLightSampler).
/// power[i] and bounds[i] describe light i.
std::unique_ptr<LightSampler> makeLightSampler(LightSamplerKind kind,
                                               const std::vector<float>& power,
                                               const std::vector<LightBounds>& bounds);

}  // namespace tray

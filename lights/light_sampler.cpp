#include "lights/light_sampler.h"

#include "core/error.h"
#include "lights/bvh_light_sampler.h"
#include "lights/power_light_sampler.h"

namespace tray {

LightSamplerKind lightSamplerKind(const std::string& name) {
  if (name == "power") return LightSamplerKind::kPower;
  if (name == "bvh") return LightSamplerKind::kBvh;
  throw Error("--light-sampler '" + name + "': expected power or bvh");
}

std::unique_ptr<LightSampler> makeLightSampler(LightSamplerKind kind,
                                               const std::vector<float>& power,
                                               const std::vector<LightBounds>& bounds) {
  if (kind == LightSamplerKind::kPower) return std::make_unique<PowerLightSampler>(power);
  return std::make_unique<BvhLightSampler>(bounds);
}

}  // namespace tray

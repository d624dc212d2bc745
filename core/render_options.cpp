#include "core/render_options.h"

#include "core/animation_time.h"
#include "core/filter.h"
#include "core/pixel_sampler.h"
#include "core/sampler.h"

namespace tray {

const std::vector<OptionSpec>& renderOptions() {
  static const std::vector<OptionSpec> specs = [] {
    std::vector<OptionSpec> s = {
        choiceOption("integrator", "whitted", {}, "integrator"),
        intOption("spp", 1, 1, 1 << 20, "samples per pixel"),
        intOption("seed", 0, 0, std::numeric_limits<int64_t>::max(), "random seed"),
        Sampler::option(),
        PixelSampler::option(),
        Filter::option(),
    };
    const auto& animation = animationOptions();  // --time, --fps, --animation
    s.insert(s.end(), animation.begin(), animation.end());
    return s;
  }();
  return specs;
}

}  // namespace tray

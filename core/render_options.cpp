#include "core/render_options.h"

#include "core/animation_time.h"
#include "core/filter.h"
#include "core/pixel_sampler.h"
#include "core/sampler.h"

namespace tray {

const std::vector<OptionSpec>& renderOptions() {
  static const std::vector<OptionSpec> specs = {
      choiceOption("integrator", "whitted", {}, "integrator"),
      intOption("spp", 1, 1, 1 << 20, "samples per pixel"),
      intOption("seed", 0, 0, std::numeric_limits<int64_t>::max(), "random seed"),
      Sampler::option(),
      PixelSampler::option(),
      Filter::option(),
  };
  static const std::vector<OptionSpec> all = withAnimationOptions(specs);  // --time, --fps, ...
  return all;
}

}  // namespace tray

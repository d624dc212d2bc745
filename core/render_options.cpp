#include "core/render_options.h"

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
      // Read by io/environment_map.cpp (applyEnvironmentOptions) before the render starts.
      choiceOption("env", "", {},
                   "equirectangular HDR environment map (.exr, .hdr): replaces the scene's "
                   "TRAY_environment image or background"),
      floatOption("env-rotate", 0, -36000, 36000,
                  "environment rotation in degrees about +Y (overrides TRAY_environment)"),
      floatOption("env-intensity", 1, 0, 1e30f,
                  "environment radiance scale (overrides TRAY_environment)"),
  };
  return specs;
}

}  // namespace tray

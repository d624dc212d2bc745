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
      // Renders in passes (render/pass_renderer.h, docs/adaptive-sampling.md) when either of
      // the next two is set; --spp is then the most a pixel takes.
      floatOption("noise-threshold", 0.0f, 0.0f, 1e6f,
                  "adaptive sampling: the relative error at which a pixel with --min-spp "
                  "samples stops (e.g. 0.05; --noise-rule says how it grows with samples); 0: "
                  "every pixel takes --spp"),
      choiceOption("noise-rule", "mse", {"mse", "even"},
                   "adaptive sampling: mse stops a pixel of n samples below threshold x "
                   "sqrt(n / min-spp), the least image error for the samples spent; even stops "
                   "every pixel below the threshold (equal error, as Cycles)"),
      choiceOption("noise-metric", "relative", {"relative", "absolute"},
                   "adaptive sampling: relative measures a pixel's error against its value "
                   "(relMSE, what the eye sees after tone mapping); absolute in radiance units "
                   "(RMSE: spends more on bright pixels; --noise-threshold is then a radiance)"),
      choiceOption("noise-decision", "wide", {"wide", "neighbours", "max", "pixel"},
                   "adaptive sampling: wide stops a pixel on the RMS error of the 24 others of "
                   "its 5x5 (unbiased); neighbours on its 8 neighbours' mean error (dark by up "
                   "to 1.7% at high thresholds where bright paths are rare); max on their "
                   "largest; pixel also on its own, as Cycles: lower error where noise is local "
                   "to pixels, but the image comes out 0.1-0.5% dark"),
      intOption("min-spp", 16, 1, 1 << 20,
                "adaptive sampling: samples every pixel takes before it may stop (at most --spp)"),
      floatOption("time-limit", 0.0f, 0.0f, 1e9f,
                  "seconds after which the render ends, every pixel with whole steps of "
                  "samples (not reproducible; the first pass always completes); 0: none"),
      intOption("seed", 0, 0, std::numeric_limits<int64_t>::max(), "random seed"),
      Sampler::option(),
      PixelSampler::option(),
      Filter::option(),
      // Compositing: camera rays that escape give RGBA 0 while the environment still lights
      // the scene (Integrator::cameraLi); also TRAY_environment "transparent".
      flagOption("transparent",
                 "transparent background: escaped camera rays give RGBA 0 (premultiplied), the "
                 "environment still lights the scene"),
      // Read by the front end (render_setup.h addDefaultLightingIfUnlit), not the integrator.
      flagOption("no-default-light",
                 "never add TRay's default headlight and 0.1 environment to an unlit scene"),
      // Depth of field: set values override the camera's TRAY_camera (applyLensOptions).
      // At most 1e17: the bound of every coordinate a ray is made from (render/ray_range.h).
      floatOption("lens-radius", 0.0f, 0.0f, 1e17f,
                  "thin-lens aperture radius in scene units (0: pinhole; unset: the camera's "
                  "TRAY_camera lensRadius)"),
      floatOption("focus-distance", 0.0f, 0.0f, 1e17f,
                  "view depth of the plane in focus (unset: the camera's TRAY_camera "
                  "focusDistance)"),
      intOption("aperture-blades", 0, 0, 64,
                "aperture shape: 0 round, N >= 3 a regular N-gon (bokeh)"),
      // Read by io/environment_map.cpp (applyEnvironmentOptions) before the render starts.
      choiceOption("env", "", {},
                   "equirectangular HDR environment map (.exr, .hdr): replaces the scene's "
                   "TRAY_environment image or background"),
      floatOption("env-rotate", 0, -36000, 36000,
                  "environment rotation in degrees about +Y (overrides TRAY_environment)"),
      floatOption("env-intensity", 1, 0, 1e30f,
                  "environment radiance scale (overrides TRAY_environment)"),
      // Read by the glTF loader (gltf/gltf_variants.h); the bad value's message lists them.
      choiceOption("variant", "none", {},
                   "KHR_materials_variants: the material variant to render, by name or index; "
                   "none: each primitive's own material"),
  };
  static const std::vector<OptionSpec> all = withAnimationOptions(specs);  // --time, --fps, ...
  return all;
}

bool rendersInPasses(const RenderSettings& settings) {
  return settings.getFloat("noise-threshold") > 0 || settings.getFloat("time-limit") > 0;
}

}  // namespace tray

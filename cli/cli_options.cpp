#include "cli/cli_options.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "accel/registry.h"
#include "cli/option_cli.h"
#include "cli/options_doc.h"
#include "film/aov.h"

namespace {

/// The largest count of MB or seconds an option takes: 1e9 MB is a petabyte, 1e9 s 30 years;
/// beyond, MB would overflow when made bytes.
constexpr double kLargest = 1e9;

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// Rejects a leading minus before CLI11 converts: it would store --seed -1 as 2^64 - 1, and an
/// index of -1 would mean "absent" (the default camera or scene) instead of an error.
CLI::Validator nonNegative(const std::string& expected) {
  return CLI::Validator(
      [expected](std::string& value) -> std::string {
        const size_t first = value.find_first_not_of(" \t");
        if (first != std::string::npos && value[first] == '-')
          return "'" + value + "' is negative: expected " + expected;
        return {};
      },
      "", "non-negative");
}

/// A finite number in [lo, hi] (hi infinite: no upper bound). CLI11's Range and
/// NonNegativeNumber let NaN through: every comparison with it is false.
CLI::Validator finiteIn(double lo, double hi, const std::string& expected) {
  std::ostringstream range;  // for --help and docs/options.md, as CLI::Range wrote it
  if (std::isinf(hi))
    range << "FINITE >= " << lo;
  else
    range << "FINITE in [" << lo << " - " << hi << "]";
  return CLI::Validator(
      [lo, hi, expected](std::string& value) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(value, v) || !std::isfinite(v) || v < lo || v > hi)
          return "'" + value + "': expected " + expected;
        return {};
      },
      range.str(), "finite number");
}

/// The --help groups of the options declared here (those made from declarations are grouped
/// by cli/option_cli.cpp). A name missing from `app` is a mistake in this table.
void groupOptions(CLI::App& app) {
  const std::vector<std::pair<const char*, std::vector<const char*>>> groups = {
      {"Scene and camera",
       {"--camera", "--scene", "--resolution", "--allow-any-path", "--ignore-required-extensions",
        "--max-memory", "--texture-memory"}},
      {"Output",
       {"--output", "--float", "--output-colorspace", "--display", "--view", "--aov",
        "--cryptomatte-ranks", "--aa-heatmap"}},
      {"Frames, farm parts and checkpoints",
       {"--frames", "--region", "--sample-range", "--checkpoint", "--resume"}},
      {"Running",
       {"--threads", "--accel", "--quiet", "--progress", "--progress-step", "--progress-seconds",
        "--preview", "--help", "--version"}},
  };
  for (const auto& [group, names] : groups)
    for (const char* name : names) app.get_option(name)->group(group);
}

}  // namespace

void addCliOptions(CLI::App& app, CliOptions& o) {
  app.set_version_flag("--version", std::string("tray-render ") + TRAY_VERSION);
  app.add_option("scene", o.scenePath, "glTF 2.0 scene (.gltf or .glb)")->required();
  app.add_option("-o,--output", o.outputs,
                 "output image(s): .exr (scene-linear) or .png/.jpg (display-referred); repeatable")
      ->capture_default_str();
  // --integrator, --spp, --seed, --sampler, --pixel-sampler, --filter and every registered
  // integrator's own options (--max-depth, --aa-depth, ...), from their declarations (which
  // refuse an empty value themselves: the loop below skips them).
  const size_t declaredFrom = app.get_options().size();
  tray::addRenderOptions(app, o.settings);
  const size_t declaredTo = app.get_options().size();
  app.add_option("--aa-heatmap", o.aaHeatmap, "write an image of camera rays per pixel (PNG/EXR)");
  app.add_option("--threads", o.threads,
                 "threads for the whole job, the accelerator's build included (0: all cores)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  app.add_option("--resolution", o.resolution,
                 "image size WxH (default 640 wide, height from the camera)");
  app.add_option("--camera", o.camera,
                 "the glTF camera to render: N for the file's cameras[N], or a node or camera "
                 "name (default: the placed camera of lowest index)")
      ->check(nonNegative("a camera index >= 0 or a name (omit --camera for the default)"));
  app.add_option("--scene", o.scene, "index of the glTF scene (default: the file's default scene)")
      ->check(nonNegative("a scene index >= 0 (omit --scene for the file's default scene)"));
  app.add_option("--accel", o.accel, "accelerator: " + joined(tray::acceleratorNames()))
      ->capture_default_str();
  app.add_flag("--float", o.floatOutput, "write 32-bit float EXR (default half)");
  app.add_option("--output-colorspace", o.outputColorspace,
                 "OCIO colorspace (name, alias or role) of EXR output (default: the config's "
                 "linear Rec.709, lin_rec709 in TRay's; else its scene_linear role)");
  app.add_option("--display", o.display, "OCIO display for PNG/JPG output (default: sRGB)");
  app.add_option("--view", o.view, "OCIO view for PNG/JPG output (default: the display's first)");
  app.add_flag("--allow-any-path", o.allowAnyPath, "let scene URIs leave the scene's folder");
  app.add_flag("--ignore-required-extensions", o.ignoreRequiredExtensions,
               "render a glTF whose required extensions TRay lacks (with a warning)");
  app.add_option("--instance-arrays", o.instanceArrayMin,
                 "EXT_mesh_gpu_instancing sets of at least this many instances load as one "
                 "instance array each (docs/instancing.md); 0: one object per instance")
      ->capture_default_str();
  app.add_option("--aov", o.aovs,
                 "extra EXR layers: comma-separated from " + joined(tray::AovSet::known()) +
                     ", cryptomatte (= crypto_object,crypto_material), lightpaths (the path "
                     "tracer's 7 light-path layers), or all (every layer the integrator makes)");
  app.add_option("--cryptomatte-ranks", o.cryptomatteRanks,
                 "Cryptomatte: ids kept per pixel and type (2 per EXR layer)")
      ->check(CLI::Range(1, 32))
      ->capture_default_str();
  app.add_option("--region", o.region,
                 "render pixels x0..x1-1, y0..y1-1 only: an EXR data window of the full image");
  app.add_option("--sample-range", o.sampleRange,
                 "render samples a..b-1 of each pixel only: a part for tray-merge");
  app.add_option("--checkpoint", o.checkpointSeconds,
                 "every SECONDS, write the progress so far to the first .exr output")
      ->check(finiteIn(0, kLargest, "a number of seconds in [0, 1e9]"));
  app.add_flag("--resume", o.resume, "continue the render saved in the first .exr output");
  app.add_option("--max-memory", o.maxMemoryMB,
                 "refuse a scene whose buffers, textures and geometry need more than MB "
                 "(default: 80% of physical memory; 0: no limit)")
      ->check(finiteIn(0, kLargest, "a number of MB in [0, 1e9] (0: no limit)"));
  app.add_option("--texture-memory", o.textureMemoryMB,
                 "texture tile budget in MB: TRay filters when its MIP tiles fit, else OIIO's "
                 "cache pages them within it (default: all the scene's texture levels as "
                 "float tiles, at least 128 and at most a quarter of physical memory; never "
                 "changes pixels)")
      ->check(finiteIn(0, kLargest, "a number of MB in [0, 1e9]"));
  app.add_flag("-q,--quiet", o.quiet, "no progress bar or summary (--progress none)");
  app.add_option("--progress", o.progress,
                 "bar (on a terminal), plain (one line 'progress P% elapsed S s eta S s' per "
                 "--progress-step percent or --progress-seconds, for farm logs) or none")
      ->check(CLI::IsMember({"bar", "plain", "none"}))
      ->capture_default_str();
  app.add_option("--progress-step", o.progressSettings.stepPercent,
                 "--progress plain: a line each time progress passes a multiple of PERCENT")
      ->check(finiteIn(0.1, 100.0, "a percentage in [0.1, 100]"))
      ->capture_default_str();
  app.add_option("--progress-seconds", o.progressSettings.intervalSeconds,
                 "--progress plain: a line at least every SECONDS (0: only by --progress-step)")
      ->check(finiteIn(0, kLargest, "a number of seconds in [0, 1e9]"))
      ->capture_default_str();
  // A flag with an optional value: --preview (port 8642) or --preview=PORT (--preview=any: a
  // free port). CLI11 reads a flag's "=0" as "not given", hence "any" rather than 0.
  app.add_flag("--preview{8642}", o.previewPort,
               "serve a live preview of the render at http://127.0.0.1:PORT/ (--preview=PORT; "
               "default 8642; any: a free port): the image so far, its samples and time left, "
               "a choice of layer (docs/preview.md)")
      ->check(CLI::Validator(
          [](std::string& value) -> std::string {
            int port = 0;
            if (value == "any" ||
                (CLI::detail::lexical_cast(value, port) && port >= 1 && port <= 65535))
              return {};
            return "'" + value + "': expected a port in [1, 65535] or any";
          },
          "PORT", "port"));
  app.add_option("--frames", o.frames,
                 "render frames FIRST-LAST of the animation at --fps, each at time frame / fps, "
                 "to outputs named by a pattern: -o out.####.exr (or out.%04d.exr)");
  // An option given an empty value (`--aov ''`, `--camera ''`) is a mistake, not its default
  // (issue 40): the command line's own options refuse one as the declared ones do.
  const std::vector<CLI::Option*> options = app.get_options();
  for (size_t i = 0; i < options.size(); ++i)
    if ((i < declaredFrom || i >= declaredTo) && options[i]->get_type_size() != 0 &&
        !options[i]->get_positional())
      options[i]->check(tray::nonEmptyValue());
  groupOptions(app);
  tray::addHelpMarkdownFlag(app, "Running");
}

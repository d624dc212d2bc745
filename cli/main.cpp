// tray-render: the command line. Parses options, loads the scene, renders, writes images.
// Exit codes: 0 ok, 1 render error, 2 bad input or usage, 130 / 143 interrupted (SIGINT /
// SIGTERM; the image so far is written).
#include <CLI/CLI.hpp>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "accel/registry.h"
#include "cli/farm.h"
#include "cli/frames.h"
#include "cli/option_cli.h"
#include "cli/progress.h"
#include "core/accelerator.h"
#include "core/animation_time.h"
#include "core/aov.h"
#include "core/camera_matrices.h"
#include "core/cryptomatte.h"
#include "core/error.h"
#include "core/render_setup.h"
#include "core/renderer.h"
#include "integrators/adaptive.h"
#include "integrators/registry.h"
#include "io/environment_map.h"
#include "io/gltf_loader.h"
#include "io/image_output.h"
#include "io/scene_hash.h"

namespace {

struct CliOptions {
  std::string scenePath;
  std::vector<std::string> outputs{"out.exr"};
  std::string resolution;
  std::string camera;  ///< --camera: a glTF camera index or a node/camera name; "" default
  int scene = -1;
  int threads = 0;
  std::string accel = "embree";
  bool floatOutput = false;
  std::string outputColorspace;  ///< empty: the config's linear Rec.709, else scene_linear
  std::string display, view;
  bool allowAnyPath = false;
  bool ignoreRequiredExtensions = false;
  bool quiet = false;
  std::string progress = "bar";  ///< --progress bar|plain|none
  tray::ProgressSettings progressSettings;
  std::string sceneHash;  ///< sceneContentHash, computed once for all frames; empty: not yet
  std::string aovs;
  int cryptomatteRanks = 6;
  std::string aaHeatmap;
  std::string region, sampleRange;
  double checkpointSeconds = 0;
  bool resume = false;
  int testInterruptAfterTiles = 0;
  std::string frames;  ///< --frames A-B; empty: one image
  double maxMemoryMB = -1;     ///< -1: 80% of physical memory; 0: no limit
  double textureMemoryMB = 0;  ///< 0: TextureSampler::kDefaultCacheMB
  tray::RenderSettings settings;
};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

/// What run() is doing, for the out-of-memory message (std::bad_alloc says nothing itself).
const char* gPhase = "starting";

/// --max-memory's default: 80% of MemTotal (0, no limit, when /proc/meminfo cannot tell).
double defaultMaxMemoryMB() {
  FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return 0;
  unsigned long long kB = 0;
  char line[256];
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "MemTotal: %llu kB", &kB) == 1) break;
  std::fclose(f);
  return double(kB) / 1024.0 * 0.8;
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

/// Output mistakes (format, folder, colorspace, display/view, $OCIO, checkpoints without an
/// EXR), before any work: on a farm, a mistake found after the render costs hours.
void checkOutputsOf(const CliOptions& o) {
  tray::ImageOutputOptions check;
  check.colorspace = o.outputColorspace, check.display = o.display, check.view = o.view;
  tray::checkOutputs(o.outputs, check);
  if (!o.aaHeatmap.empty()) tray::checkOutputs({o.aaHeatmap}, check);
  if ((o.checkpointSeconds > 0 || o.resume) && tray::firstExr(o.outputs).empty())
    throw tray::Error("--checkpoint and --resume need an .exr output (-o NAME.exr)");
}

tray::LoadOptions loadOptionsOf(const CliOptions& o) {
  tray::LoadOptions loadOptions;
  loadOptions.scene = o.scene;
  loadOptions.allowAnyPath = o.allowAnyPath;
  loadOptions.time = tray::animationTime(o.settings);
  loadOptions.animation = o.settings.getString("animation");
  const double maxMemoryMB = o.maxMemoryMB < 0 ? defaultMaxMemoryMB() : o.maxMemoryMB;
  loadOptions.maxMemoryBytes = uint64_t(maxMemoryMB * 1048576.0);
  loadOptions.textureCacheMB = o.textureMemoryMB;
  loadOptions.ignoreRequiredExtensions = o.ignoreRequiredExtensions;
  return loadOptions;
}

/// One image. `document`, when given (--frames), is the file parsed once: the frame's scene
/// is converted from it at the frame's time instead of reading the file again.
int run(const CliOptions& o, const tray::GltfDocument* document = nullptr) {
  // First: a signal while the scene loads also stops the render (at its first pixel).
  const std::atomic<bool>& stop = tray::installInterruptHandlers();
  checkOutputsOf(o);
  gPhase = "loading the scene";
  const tray::LoadOptions loadOptions = loadOptionsOf(o);
  tray::LoadReport report;
  tray::Scene scene = document ? document->scene(loadOptions, &report)
                               : tray::loadGltf(o.scenePath, loadOptions, &report);
  scene.sourcePath = o.scenePath;
  tray::applyEnvironmentOptions(scene, o.settings, &report.warnings);  // --env: read and checked
  for (const auto& w : report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  const int placedCamera = tray::findCamera(scene, o.camera);
  tray::CameraDesc cam = tray::chooseCamera(scene, o.camera);
  tray::applyLensOptions(cam, o.settings);
  bool defaultLight = false;
  if (o.settings.getBool("no-default-light")) {
    // Nothing added: an unlit asset renders black (or lit by emitters too weak to count).
  } else if ((defaultLight = tray::addDefaultLightingIfUnlit(scene, cam)))
    std::fprintf(stderr,
                 "warning: %s has no lights of meaningful power: using TRay's default headlight and a 0.1 "
                 "environment (docs/scene-format.md; --no-default-light turns it off)\n",
                 o.scenePath.c_str());
  const tray::ImageSize size = tray::resolveImageSize(o.resolution, cam);
  const int width = size.width, height = size.height;
  auto camera = tray::Camera::create(cam, width, height);
  {  // The accelerator's estimate, with what the loader counted, before it is built.
    tray::MemoryEstimate need = report.memory;
    for (const auto& m : scene.meshes) need.geometry += m.triangleCount();
    need.geometry *= tray::kGeometryBytesPerTriangle;
    tray::checkMemory(o.scenePath, need, loadOptions.maxMemoryBytes);
  }
  gPhase = "building the accelerator";
  auto accel = tray::makeAccelerator(o.accel, scene);
  if (defaultLight && tray::useHeadlightIfEnclosed(scene, cam, *accel))
    std::fprintf(stderr,
                 "warning: %s: the camera is enclosed (a sky box?) and the default key light "
                 "cannot get in: a headlight at the camera replaces it\n",
                 o.scenePath.c_str());
  gPhase = "rendering";
  tray::RenderContext ctx{scene, *accel, *camera, o.settings, width, height};
  auto integrator = tray::makeIntegrator(ctx);
  const std::string integratorName = o.settings.getString("integrator");
  const int spp = o.settings.getInt("spp");

  const tray::PixelRegion region = tray::parseRegion(o.region, width, height);
  const tray::SampleRange range =
      tray::parseSampleRange(o.sampleRange, integrator->samplesPerPixel(), integratorName);
  const std::vector<std::string> aovNames = tray::AovSet::parse(o.aovs);
  if (!o.sampleRange.empty() && tray::Cryptomatte::requested(aovNames))
    throw tray::Error(
        "--sample-range with Cryptomatte AOVs: each part would keep only its own "
        "top-ranked ids, which cannot be merged exactly (split by --region instead)");
  const bool part = o.region.size() || o.sampleRange.size();
  const std::string checkpointPath = tray::firstExr(o.outputs);
  const std::string output = std::string(o.floatOutput ? "float," : "half,") +
                             (o.outputColorspace.empty() ? "default" : o.outputColorspace);
  const std::string job = tray::jobSignature(
      o.settings, {o.scenePath, o.scene, placedCamera, width, height, o.accel,
                   o.aovs + (o.aaHeatmap.empty() ? "" : "+samples"),
                   o.sceneHash.empty() ? tray::sceneContentHash(o.scenePath, o.allowAnyPath)
                                       : o.sceneHash,
                   output});

  tray::Film film(region.width(), region.height());
  tray::RenderState state;
  double previousSeconds = 0;
  if (o.resume) {
    if (!std::filesystem::exists(checkpointPath)) {
      std::fprintf(stderr, "warning: %s: no checkpoint to resume: rendering from the start\n",
                   checkpointPath.c_str());
    } else if (!tray::loadCheckpoint(checkpointPath, job, region, width, height, range, film, state,
                                     previousSeconds)) {
      if (!o.quiet)
        std::printf("%s: already finished: nothing to resume\n", checkpointPath.c_str());
      return 0;
    }
  }
  tray::Progress progress(o.progressSettings);
  tray::RenderOptions renderOptions;
  renderOptions.threads = o.threads;
  renderOptions.aovs = aovNames;
  renderOptions.cryptomatteRanks = o.cryptomatteRanks;
  if (!o.aaHeatmap.empty()) renderOptions.aovs.push_back("samples");  // the heatmap's source
  renderOptions.x0 = region.x0, renderOptions.y0 = region.y0;
  renderOptions.sampleBegin = range.begin, renderOptions.sampleEnd = range.end;
  renderOptions.stop = &stop;
  int tiles = 0;  // --test-interrupt-after-tiles: a real SIGINT at a chosen point
  renderOptions.onProgress = [&](double f) {
    if (!stop.load()) progress.update(f);  // tiles cut short by a stop are not progress
    if (++tiles == o.testInterruptAfterTiles) std::raise(SIGINT);
  };

  tray::ImageOutputOptions out;
  out.halfFloat = !o.floatOutput;
  out.colorspace = o.outputColorspace;
  out.display = o.display;
  out.view = o.view;
  out.fullWidth = width, out.fullHeight = height;
  out.xOffset = region.x0, out.yOffset = region.y0;
  out.matrixMetadata = {{"worldToCamera", tray::exrWorldToCamera(cam)},
                        {"worldToNDC", tray::exrWorldToNdc(cam, width, height)}};
  // Writes `film` with the metadata of this render; partial renders and parts carry their state.
  // `final`: the render's outputs, not a checkpoint (warned about once, at the end).
  auto write = [&](tray::Film& image, const tray::RenderState& now, double seconds,
                   const std::vector<std::string>& paths, bool final) {
    const size_t done = now.pixelsDone(), all = now.done.size();
    tray::ImageOutputOptions w = out;
    w.stringMetadata = {{"tray:version", TRAY_VERSION},
                        {"tray:accelerator", o.accel},
                        {"tray:scene", o.scenePath},
                        {"tray:status", done == all ? "complete" : "partial"},
                        {"tray:job", job}};
    w.floatMetadata = {{"tray:renderSeconds", float(seconds)},
                       {"tray:pixelsDone", float(done)},
                       {"tray:pixelsTotal", float(all)},
                       {"tray:sampleBegin", float(range.begin)},
                       {"tray:sampleEnd", float(range.end)},
                       {"tray:samplesPerPixel", float(integrator->samplesPerPixel())}};
    tray::addOptionMetadata(o.settings, w);  // tray:integrator, tray:spp, tray:maxDepth, ...
    if (integrator->samplesPerPixel() > 0)  // adaptive: the samples AOV counts them per pixel
      w.floatMetadata.emplace_back("tray:samplesDone",
                                   float(done) * float(range.end - range.begin));
    if (part || done < all) tray::storeState(now, image);
    const std::vector<size_t> clamped = tray::writeImages(image, paths, w);  // all or nothing
    for (size_t i = 0; i < paths.size(); ++i)
      if (clamped[i] && final)
        std::fprintf(stderr, "warning: %s\n", tray::halfClampWarning(paths[i], clamped[i]).c_str());
  };
  const auto started = std::chrono::steady_clock::now();
  if (o.checkpointSeconds > 0) {
    renderOptions.checkpointSeconds = o.checkpointSeconds;
    renderOptions.onCheckpoint = [&](const tray::Film& f, const tray::RenderState& s) {
      tray::Film copy = f;
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      try {  // a failed checkpoint (full disk) costs the safety net, not the render
        write(copy, s, previousSeconds + elapsed, {checkpointPath}, false);
      } catch (const tray::Error& e) {
        std::fprintf(stderr, "warning: checkpoint not written: %s\n", e.what());
      }
    };
  }
  tray::RenderStats stats = tray::renderImage(*integrator, film, state, renderOptions);
  progress.finish(!stats.interrupted);

  gPhase = "writing images";
  write(film, state, previousSeconds + stats.seconds, o.outputs, true);
  if (!o.aaHeatmap.empty() && !stats.interrupted)
    tray::writeImage(tray::samplesHeatmap(film), o.aaHeatmap);
  if (stats.interrupted) {
    const int sig = tray::interruptSignal();
    std::fprintf(stderr, "tray-render: interrupted (%s): %zu of %zu pixels done, written to %s\n",
                 sig == SIGTERM ? "SIGTERM" : "SIGINT", stats.pixelsDone, state.done.size(),
                 o.outputs.front().c_str());
    return 128 + (sig ? sig : SIGINT);
  }

  if (!o.quiet) {
    std::printf("%s: %dx%d, %d spp, %s on %s: %.3f s, %.2f M rays, %.2f Mrays/s",
                o.scenePath.c_str(), width, height, spp, integratorName.c_str(),
                o.accel.c_str(), stats.seconds, stats.rays.total() * 1e-6, stats.mraysPerSecond());
    if (stats.rays.nanSamples)
      std::printf(", %llu NaN/Inf samples discarded", (unsigned long long)stats.rays.nanSamples);
    std::printf("\n");
  }
  return 0;
}

/// --frames: each frame rendered in turn from the file parsed once (tray::GltfDocument; the
/// scene, posed at the frame's time, is converted anew for each frame), with --time set to
/// frame / fps so that its job signature and EXR metadata say which time it shows. Stops at the
/// first frame that fails or is interrupted.
int runFrames(const CliOptions& o) {
  const tray::FrameRange range = tray::parseFrameRange(o.frames);
  const float fps = o.settings.getFloat("fps");
  {  // the first frame's outputs, checked before the file is read
    CliOptions first = o;
    for (auto& path : first.outputs) path = tray::framePath(path, range.first);
    if (!first.aaHeatmap.empty()) first.aaHeatmap = tray::framePath(first.aaHeatmap, range.first);
    checkOutputsOf(first);
  }
  gPhase = "loading the scene";
  tray::LoadReport parseReport;
  const tray::GltfDocument document(o.scenePath, loadOptionsOf(o), &parseReport);
  for (const auto& w : parseReport.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  CliOptions hashed = o;  // the file's content, hashed once for every frame's job signature
  hashed.sceneHash = tray::sceneContentHash(o.scenePath, o.allowAnyPath);
  for (int64_t f = range.first; f <= range.last; ++f) {
    CliOptions frame = hashed;
    for (auto& path : frame.outputs) path = tray::framePath(path, f);
    if (!frame.aaHeatmap.empty()) frame.aaHeatmap = tray::framePath(frame.aaHeatmap, f);
    frame.settings.set("time", tray::frameTime(f, fps));
    if (!o.quiet)
      std::printf("frame %lld (time %s s): %s\n", (long long)f,
                  frame.settings.getString("time").c_str(), frame.outputs.front().c_str());
    if (const int rc = run(frame, &document); rc != 0) return rc;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CliOptions o;

  CLI::App app{"TRay: offline renderer for glTF 2.0 scenes (Embree, Whitted and path tracing)"};
  app.set_version_flag("--version", std::string("tray-render ") + TRAY_VERSION);
  app.add_option("scene", o.scenePath, "glTF 2.0 scene (.gltf or .glb)")->required();
  app.add_option("-o,--output", o.outputs,
                 "output image(s): .exr (scene-linear) or .png/.jpg (display-referred); repeatable")
      ->capture_default_str();
  // --integrator, --spp, --seed, --sampler, --pixel-sampler, --filter and every registered
  // integrator's own options (--max-depth, --aa-depth, ...), from their declarations.
  tray::addRenderOptions(app, o.settings);
  app.add_option("--aa-heatmap", o.aaHeatmap, "write an image of camera rays per pixel (PNG/EXR)");
  app.add_option("--threads", o.threads, "worker threads (0: all cores)")
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
  app.add_option("--aov", o.aovs,
                 "extra EXR layers: comma-separated from " + joined(tray::AovSet::known()) +
                     ", cryptomatte (= crypto_object,crypto_material), lightpaths (the path "
                     "tracer's 7 light-path layers), or all (all but the light paths)");
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
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--resume", o.resume, "continue the render saved in the first .exr output");
  app.add_option("--test-interrupt-after-tiles", o.testInterruptAfterTiles)->group("");
  app.add_option("--max-memory", o.maxMemoryMB,
                 "refuse a scene whose buffers, textures and geometry need more than MB "
                 "(default: 80% of physical memory; 0: no limit)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--texture-memory", o.textureMemoryMB,
                 "texture cache budget in MB (default 128; never changes pixels)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("-q,--quiet", o.quiet, "no progress bar or summary (--progress none)");
  app.add_option("--progress", o.progress,
                 "bar (on a terminal), plain (one line 'progress P% elapsed S s eta S s' per "
                 "--progress-step percent or --progress-seconds, for farm logs) or none")
      ->check(CLI::IsMember({"bar", "plain", "none"}))
      ->capture_default_str();
  app.add_option("--progress-step", o.progressSettings.stepPercent,
                 "--progress plain: a line each time progress passes a multiple of PERCENT")
      ->check(CLI::Range(0.1, 100.0))
      ->capture_default_str();
  app.add_option("--progress-seconds", o.progressSettings.intervalSeconds,
                 "--progress plain: a line at least every SECONDS (0: only by --progress-step)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--frames", o.frames,
                 "render frames FIRST-LAST of the animation at --fps, each at time frame / fps, "
                 "to outputs named by a pattern: -o out.####.exr (or out.%04d.exr)");

  // One line, in the form of every other error (CLI11 adds a second "Run with --help" line).
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("tray-render: error: ") + e.what() + " (see --help)\n";
  });
  try {
    app.parse(argc, argv);
    tray::validateOptions(o.settings);  // ranges and choices, before any loading
    tray::animationTime(o.settings);     // --time: "static" or seconds
    if (!o.frames.empty()) {
      tray::parseFrameRange(o.frames);
      if (o.settings.isSet("time"))
        throw tray::Error("--frames sets the time of each frame (frame / fps): drop --time");
    }
    tray::checkFramePatterns(o.outputs, !o.frames.empty());
    o.progressSettings.mode =
        o.quiet ? tray::ProgressMode::kNone : tray::parseProgressMode(o.progress);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const tray::Error& e) {
    std::fprintf(stderr, "tray-render: error: %s\n", e.what());
    return 2;
  }
  try {
    return o.frames.empty() ? run(o) : runFrames(o);
  } catch (const tray::Error& e) {
    std::fprintf(stderr, "tray-render: error: %s\n", e.what());
    return e.kind() == tray::Error::Kind::kInput ? 2 : 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr,
                 "tray-render: error: out of memory while %s (%s; a smaller --resolution, "
                 "fewer --aov layers or more memory may help)\n",
                 gPhase, o.scenePath.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tray-render: error: %s\n", e.what());
    return 1;
  }
}

// tray-render: the command line. Parses options, loads the scene, renders, writes images.
// Exit codes: 0 ok, 1 render error, 2 bad input or usage, 130 / 143 interrupted (SIGINT /
// SIGTERM; the image so far is written).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "accel/registry.h"
#include "cli/cli_options.h"
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


/// The job's content: the scene and every file it names, and the --env map, whose pixels are
/// not in the option's value (its path).
std::string contentHashOf(const CliOptions& o) {
  const std::string env = o.settings.getString("env");
  return tray::sceneContentHash(o.scenePath, o.allowAnyPath,
                                env.empty() ? std::vector<std::string>{}
                                            : std::vector<std::string>{env});
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
  if (const auto shutter = tray::shutterOf(o.settings); shutter && loadOptions.time) {
    const float fps = o.settings.getFloat("fps");
    loadOptions.shutterOpen = shutter->at(*loadOptions.time, fps, 0.0f);
    loadOptions.shutterClose = shutter->at(*loadOptions.time, fps, 1.0f);
    loadOptions.motionSteps = int(o.settings.getInt("motion-steps"));
  }
  const std::vector<std::string> aovs = tray::AovSet::parse(o.aovs);
  if (loadOptions.time && std::count(aovs.begin(), aovs.end(), "motion"))
    loadOptions.previousTime = *loadOptions.time - 1.0f / o.settings.getFloat("fps");
  const double maxMemoryMB = o.maxMemoryMB < 0 ? defaultMaxMemoryMB() : o.maxMemoryMB;
  loadOptions.maxMemoryBytes = uint64_t(maxMemoryMB * 1048576.0);
  loadOptions.textureCacheMB = o.textureMemoryMB;
  loadOptions.ignoreRequiredExtensions = o.ignoreRequiredExtensions;
  return loadOptions;
}

/// What a render needs before its first pixel: the scene as loaded and lit, the camera, the
/// image size and the accelerator. Filled in place: the accelerator refers to `scene`.
struct PreparedScene {
  tray::Scene scene;
  tray::CameraDesc cam;
  int placedCamera = -1;
  int width = 0, height = 0;
  std::unique_ptr<tray::Camera> camera;
  std::unique_ptr<tray::Accelerator> accel;
};

/// Loads the scene (from `document` when --frames parsed it once), applies --env and the lens
/// options, adds the default lighting if the scene is unlit, checks --max-memory and builds the
/// accelerator. Warnings go to stderr.
void prepareScene(const CliOptions& o, const tray::GltfDocument* document, PreparedScene& p) {
  gPhase = "loading the scene";
  const tray::LoadOptions loadOptions = loadOptionsOf(o);
  tray::LoadReport report;
  p.scene = document ? document->scene(loadOptions, &report)
                     : tray::loadGltf(o.scenePath, loadOptions, &report);
  tray::Scene& scene = p.scene;
  scene.sourcePath = o.scenePath;
  tray::applyEnvironmentOptions(scene, o.settings, &report.warnings);  // --env: read and checked
  for (const auto& w : report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());

  p.placedCamera = tray::findCamera(scene, o.camera);
  p.cam = tray::chooseCamera(scene, o.camera);
  tray::applyLensOptions(p.cam, o.settings);
  bool defaultLight = false;
  if (o.settings.getBool("no-default-light")) {
    // Nothing added: an unlit asset renders black (or lit by emitters too weak to count).
  } else if ((defaultLight = tray::addDefaultLightingIfUnlit(scene, p.cam)))
    std::fprintf(stderr,
                 "warning: %s has no lights of meaningful power: using TRay's default headlight "
                 "and a 0.1 environment (docs/scene-format.md; --no-default-light turns it off)\n",
                 o.scenePath.c_str());
  const tray::ImageSize size = tray::resolveImageSize(o.resolution, p.cam);
  p.width = size.width, p.height = size.height;
  p.camera = tray::Camera::create(p.cam, p.width, p.height);
  {  // The accelerator's estimate, with what the loader counted, before it is built.
    tray::MemoryEstimate need = report.memory;
    for (const auto& m : scene.meshes)  // a deforming mesh: its triangles at every motion step
      need.geometry += m.triangleCount() * std::max<size_t>(1, m.positionSteps.size());
    need.geometry *= tray::kGeometryBytesPerTriangle;
    tray::checkMemory(o.scenePath, need, loadOptions.maxMemoryBytes);
  }
  gPhase = "building the accelerator";
  p.accel = tray::makeAccelerator(o.accel, scene);
  if (defaultLight && tray::useHeadlightIfEnclosed(scene, p.cam, *p.accel))
    std::fprintf(stderr,
                 "warning: %s: the camera is enclosed (a sky box?) and the default key light "
                 "cannot get in: a headlight at the camera replaces it\n",
                 o.scenePath.c_str());
}

/// The one line a finished render prints (unless --quiet).
void printSummary(const CliOptions& o, int width, int height, const tray::RenderStats& stats) {
  std::printf("%s: %dx%d, %d spp, %s on %s: %.3f s, %.2f M rays, %.2f Mrays/s",
              o.scenePath.c_str(), width, height, int(o.settings.getInt("spp")),
              o.settings.getString("integrator").c_str(), o.accel.c_str(), stats.seconds,
              stats.rays.total() * 1e-6, stats.mraysPerSecond());
  if (stats.rays.nanSamples)
    std::printf(", %llu NaN/Inf samples discarded", (unsigned long long)stats.rays.nanSamples);
  std::printf("\n");
}

/// The job signature of this render (tray:job): what decides its pixels but the region and
/// sample range.
std::string jobOf(const CliOptions& o, const PreparedScene& p) {
  const std::string output = std::string(o.floatOutput ? "float," : "half,") +
                             (o.outputColorspace.empty() ? "default" : o.outputColorspace);
  return tray::jobSignature(o.settings,
                            {o.scenePath, o.scene, p.placedCamera, p.width, p.height, o.accel,
                             o.aovs + (o.aaHeatmap.empty() ? "" : "+samples"),
                             o.sceneHash.empty() ? contentHashOf(o) : o.sceneHash, output});
}

/// Writes a render's film with its metadata: the final outputs, or a checkpoint.
struct ImageWriter {
  const CliOptions& o;
  tray::ImageOutputOptions out;  ///< the format and the metadata every write shares
  std::string job;
  tray::SampleRange range;
  int samplesPerPixel = 0;  ///< the integrator's; 0: adaptive
  bool part = false;        ///< --region or --sample-range: the state goes with the pixels

  /// `final`: the render's outputs, not a checkpoint (warned about once, at the end).
  void write(tray::Film& image, const tray::RenderState& now, double seconds,
             const std::vector<std::string>& paths, bool final) const {
    const size_t done = now.pixelsDone(), all = now.done.size();
    tray::ImageOutputOptions w = out;
    w.stringMetadata = {{"tray:version", TRAY_VERSION},
                        {"tray:accelerator", o.accel},
                        {"tray:scene", o.scenePath},
                        {"tray:status", done == all ? "complete" : "partial"},
                        {"tray:job", job}};
    w.floatMetadata = {
        {"tray:renderSeconds", float(seconds)}, {"tray:pixelsDone", float(done)},
        {"tray:pixelsTotal", float(all)},       {"tray:sampleBegin", float(range.begin)},
        {"tray:sampleEnd", float(range.end)},   {"tray:samplesPerPixel", float(samplesPerPixel)}};
    tray::addOptionMetadata(o.settings, w);  // tray:integrator, tray:spp, tray:maxDepth, ...
    if (samplesPerPixel > 0)                 // adaptive: the samples AOV counts them per pixel
      w.floatMetadata.emplace_back("tray:samplesDone",
                                   float(done) * float(range.end - range.begin));
    if (part || done < all) tray::storeState(now, image);
    const std::vector<size_t> clamped = tray::writeImages(image, paths, w);  // all or nothing
    for (size_t i = 0; i < paths.size(); ++i)
      if (clamped[i] && final)
        std::fprintf(stderr, "warning: %s\n", tray::halfClampWarning(paths[i], clamped[i]).c_str());
  }
};

/// The output format of a render of `p` covering `region`.
tray::ImageOutputOptions outputOptionsOf(const CliOptions& o, const PreparedScene& p,
                                         const tray::PixelRegion& region) {
  tray::ImageOutputOptions out;
  out.halfFloat = !o.floatOutput;
  out.colorspace = o.outputColorspace;
  out.display = o.display;
  out.view = o.view;
  out.fullWidth = p.width, out.fullHeight = p.height;
  out.xOffset = region.x0, out.yOffset = region.y0;
  out.matrixMetadata = {{"worldToCamera", tray::exrWorldToCamera(p.cam)},
                        {"worldToNDC", tray::exrWorldToNdc(p.cam, p.width, p.height)}};
  return out;
}

/// The renderer's options for this region, sample range and set of AOVs (progress and
/// checkpoints are added by run()).
tray::RenderOptions renderOptionsOf(const CliOptions& o, const std::vector<std::string>& aovs,
                                    const tray::PixelRegion& region, const tray::SampleRange& range,
                                    const std::atomic<bool>& stop) {
  tray::RenderOptions r;
  r.threads = o.threads;
  r.aovs = aovs;
  r.cryptomatteRanks = o.cryptomatteRanks;
  if (!o.aaHeatmap.empty()) r.aovs.push_back("samples");  // the heatmap's source
  r.x0 = region.x0, r.y0 = region.y0;
  r.sampleBegin = range.begin, r.sampleEnd = range.end;
  r.stop = &stop;
  return r;
}

/// One image. `document`, when given (--frames), is the file parsed once: the frame's scene
/// is converted from it at the frame's time instead of reading the file again.
int run(const CliOptions& o, const tray::GltfDocument* document = nullptr) {
  // First: a signal while the scene loads also stops the render (at its first pixel).
  const std::atomic<bool>& stop = tray::installInterruptHandlers();
  checkOutputsOf(o);
  PreparedScene prepared;
  prepareScene(o, document, prepared);
  gPhase = "rendering";
  tray::RenderContext ctx{prepared.scene, *prepared.accel, *prepared.camera,
                          o.settings,     prepared.width,  prepared.height};
  auto integrator = tray::makeIntegrator(ctx);
  const std::string integratorName = o.settings.getString("integrator");

  const tray::PixelRegion region = tray::parseRegion(o.region, prepared.width, prepared.height);
  const tray::SampleRange range =
      tray::parseSampleRange(o.sampleRange, integrator->samplesPerPixel(), integratorName);
  const std::vector<std::string> aovNames = tray::AovSet::parse(o.aovs);
  if (!o.sampleRange.empty() && tray::Cryptomatte::requested(aovNames))
    throw tray::Error(
        "--sample-range with Cryptomatte AOVs: each part would keep only its own "
        "top-ranked ids, which cannot be merged exactly (split by --region instead)");
  const ImageWriter writer{
      o,     outputOptionsOf(o, prepared, region), jobOf(o, prepared),
      range, integrator->samplesPerPixel(),        !o.region.empty() || !o.sampleRange.empty()};
  const std::string checkpointPath = tray::firstExr(o.outputs);

  tray::Film film(region.width(), region.height());
  tray::RenderState state;
  double previousSeconds = 0;
  if (o.resume) {
    if (!std::filesystem::exists(checkpointPath)) {
      std::fprintf(stderr, "warning: %s: no checkpoint to resume: rendering from the start\n",
                   checkpointPath.c_str());
    } else if (!tray::loadCheckpoint(checkpointPath, writer.job, region, prepared.width,
                                     prepared.height, range, film, state, previousSeconds)) {
      if (!o.quiet)
        std::printf("%s: already finished: nothing to resume\n", checkpointPath.c_str());
      return 0;
    }
  }
  tray::Progress progress(o.progressSettings);
  tray::RenderOptions renderOptions = renderOptionsOf(o, aovNames, region, range, stop);
  int tiles = 0;  // --test-interrupt-after-tiles: a real SIGINT at a chosen point
  renderOptions.onProgress = [&](double f) {
    if (!stop.load()) progress.update(f);  // tiles cut short by a stop are not progress
    if (++tiles == o.testInterruptAfterTiles) std::raise(SIGINT);
  };
  const auto started = std::chrono::steady_clock::now();
  if (o.checkpointSeconds > 0) {
    renderOptions.checkpointSeconds = o.checkpointSeconds;
    renderOptions.onCheckpoint = [&](const tray::Film& f, const tray::RenderState& s) {
      tray::Film copy = f;
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      try {  // a failed checkpoint (full disk) costs the safety net, not the render
        writer.write(copy, s, previousSeconds + elapsed, {checkpointPath}, false);
      } catch (const tray::Error& e) {
        std::fprintf(stderr, "warning: checkpoint not written: %s\n", e.what());
      }
    };
  }
  tray::RenderStats stats = tray::renderImage(*integrator, film, state, renderOptions);
  progress.finish(!stats.interrupted);

  gPhase = "writing images";
  writer.write(film, state, previousSeconds + stats.seconds, o.outputs, true);
  if (!o.aaHeatmap.empty() && !stats.interrupted)
    tray::writeImage(tray::samplesHeatmap(film), o.aaHeatmap);
  if (stats.interrupted) {
    const int sig = tray::interruptSignal();
    std::fprintf(stderr, "tray-render: interrupted (%s): %zu of %zu pixels done, written to %s\n",
                 sig == SIGTERM ? "SIGTERM" : "SIGINT", stats.pixelsDone, state.done.size(),
                 o.outputs.front().c_str());
    return 128 + (sig ? sig : SIGINT);
  }

  if (!o.quiet) printSummary(o, prepared.width, prepared.height, stats);
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
  hashed.sceneHash = contentHashOf(o);
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
  addCliOptions(app, o);

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
    if (tray::shutterOf(o.settings) && o.frames.empty() && !tray::animationTime(o.settings))
      throw tray::Error(
          "--shutter needs an animation time to open around: add --time SECONDS "
          "or --frames (the static pose does not move)");
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

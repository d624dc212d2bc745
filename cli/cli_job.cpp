#include "cli/cli_job.h"

#include "cli/frames.h"
#include "core/animation_time.h"
#include "core/error.h"
#include "core/render_options.h"
#include "integrators/registry.h"

namespace tray {

void checkCliOptions(CliOptions& o) {
  validateOptions(o.settings);  // ranges and choices, before any loading
  animationTime(o.settings);    // --time: "static" or seconds
  if (!o.frames.empty()) {
    parseFrameRange(o.frames);
    if (o.settings.isSet("time"))
      throw Error("--frames sets the time of each frame (frame / fps): drop --time");
  }
  if (shutterOf(o.settings) && o.frames.empty() && !animationTime(o.settings))
    throw Error(
        "--shutter needs an animation time to open around: add --time SECONDS "
        "or --frames (the static pose does not move)");
  checkFramePatterns(o.outputs, !o.frames.empty());
  o.progressSettings.mode = o.quiet ? ProgressMode::kNone : parseProgressMode(o.progress);
}

int previewPortOf(const CliOptions& o) {
  if (o.previewPort.empty()) return -1;
  return o.previewPort == "any" ? 0 : std::stoi(o.previewPort);  // checked by the parser
}

RenderJob jobOf(const CliOptions& o) {
  RenderJob job;
  job.scene.path = o.scenePath;
  job.scene.index = o.scene;
  job.scene.allowAnyPath = o.allowAnyPath;
  job.scene.ignoreRequiredExtensions = o.ignoreRequiredExtensions;
  job.scene.instanceArrayMin = o.instanceArrayMin;
  job.scene.maxMemoryBytes =
      o.maxMemoryMB ? uint64_t(*o.maxMemoryMB * 1048576.0) : defaultMaxMemoryBytes();
  job.scene.textureMemoryMB = o.textureMemoryMB;
  job.camera = o.camera;
  job.resolution = o.resolution;
  job.accelerator = o.accel;
  job.threads = o.threads;
  job.settings = o.settings;
  job.outputs.paths = o.outputs;
  job.outputs.floatOutput = o.floatOutput;
  job.outputs.colorspace = o.outputColorspace;
  job.outputs.display = o.display, job.outputs.view = o.view;
  job.outputs.aovs = o.aovs;
  job.outputs.cryptomatteRanks = o.cryptomatteRanks;
  job.outputs.aaHeatmap = o.aaHeatmap;
  job.part.region = o.region, job.part.sampleRange = o.sampleRange;
  job.part.checkpointSeconds = o.checkpointSeconds;
  job.part.resume = o.resume;
  return job;
}

}  // namespace tray

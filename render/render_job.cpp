#include "render/render_job.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "core/animation_time.h"
#include "core/error.h"
#include "film/aov.h"
#include "film/cryptomatte.h"
#include "gltf/scene_hash.h"
#include "integrators/adaptive.h"
#include "integrators/registry.h"
#include "io/image_output.h"
#include "render/farm.h"
#include "render/job_scene.h"
#include "render/job_writer.h"

namespace tray {
namespace {

/// Where an interrupted render's outputs go: an EXR where asked (marked partial, resumable with
/// --resume); a display-referred image (PNG, JPEG), which nothing marks partial, under
/// NAME.partial.EXT, never over the file the complete render would have written.
std::vector<std::string> interruptedOutputs(const std::vector<std::string>& paths,
                                            const RenderJobEvents& events) {
  std::vector<std::string> out;
  for (const std::string& path : paths) {
    if (isExrPath(path)) {
      out.push_back(path);
      continue;
    }
    std::filesystem::path p(path);
    p.replace_extension(".partial" + p.extension().string());
    warn(events,
         path + ": not written, the render was interrupted; the partial image is " + p.string());
    out.push_back(p.string());
  }
  return out;
}

using Clock = std::chrono::steady_clock;

/// What the job renders of the image: its region, sample range and AOV layers.
struct JobPlan {
  PixelRegion region;
  SampleRange range;
  std::vector<std::string> aovs;
};

JobPlan planOf(const RenderJob& job, const PreparedScene& scene, const Integrator& integrator) {
  JobPlan plan;
  plan.region = parseRegion(job.part.region, scene.width(), scene.height());
  plan.range = parseSampleRange(job.part.sampleRange, integrator.samplesPerPixel(),
                                job.settings.getString("integrator"));
  // "all": with the light paths when this render can split them (not in passes).
  plan.aovs = AovSet::parse(job.outputs.aovs,
                            integrator.splitsLightPaths() && !samplingPassesOf(job.settings));
  if (!job.part.sampleRange.empty() && Cryptomatte::requested(plan.aovs))
    throw Error(
        "--sample-range with Cryptomatte AOVs: each part would keep only its own "
        "top-ranked ids, which cannot be merged exactly (split by --region instead)");
  return plan;
}

/// The renderer's options for the plan, with the job's progress (checkpoints are added by
/// addCheckpoints).
RenderOptions renderOptionsOf(const RenderJob& job, const JobPlan& plan,
                              const RenderJobEvents& events) {
  RenderOptions r;
  r.threads = job.threads;
  r.aovs = plan.aovs;
  r.cryptomatteRanks = job.outputs.cryptomatteRanks;
  if (!job.outputs.aaHeatmap.empty()) r.aovs.push_back("samples");  // the heatmap's source
  r.x0 = plan.region.x0, r.y0 = plan.region.y0;
  if (!job.part.sampleRange.empty()) r.samples = plan.range;
  r.passes = samplingPassesOf(job.settings);
  r.stop = events.stop;
  r.onProgress = events.progress;
  return r;
}

/// --resume: the film and state of the checkpoint in the first .exr output, if there is one.
/// Returns false when that checkpoint is this render finished (nothing to do).
bool resume(const RenderJob& job, const JobWriter& writer, const PreparedScene& scene,
            const JobPlan& plan, Film& film, RenderState& state, RenderTime& previous,
            const RenderJobEvents& events) {
  const std::string path = firstExr(job.outputs.paths);
  if (!std::filesystem::exists(path)) {
    warn(events, path + ": no checkpoint to resume: rendering from the start");
    return true;
  }
  return loadCheckpoint(path, writer.signature(), plan.region, scene.width(), scene.height(),
                        plan.range, film, state, previous);
}

/// Every --checkpoint seconds, a copy of the pixels done so far goes to the first .exr output;
/// `previous` (resumed renders) and the time on `clock` make its render time.
/// Every events.snapshotSeconds, the copy goes to events.snapshot: the renderer's one
/// checkpoint clock runs at the shorter period, and the EXR is written when its own is due.
void addCheckpoints(RenderOptions& options, const RenderJob& job, const JobWriter& writer,
                    RenderTime previous, RenderClock clock,
                    const RenderJobEvents& events) {
  const double exrSeconds = job.part.checkpointSeconds;
  const bool snapshots = events.snapshot && events.snapshotSeconds > 0;
  options.checkpointSeconds = exrSeconds > 0 && snapshots
                                  ? std::min(exrSeconds, events.snapshotSeconds)
                                  : (exrSeconds > 0 ? exrSeconds : events.snapshotSeconds);
  auto lastExr = std::make_shared<Clock::time_point>(clock.started());
  options.onCheckpoint = [&job, &writer, &events, previous, clock, exrSeconds, snapshots,
                          lastExr](const Film& f, const RenderState& s) {
    if (snapshots) {  // alone, every call writes the EXR, as before snapshots existed
      events.snapshot(f, s);
      if (exrSeconds <= 0 ||
          std::chrono::duration<double>(Clock::now() - *lastExr).count() < exrSeconds * 0.999)
        return;
    }
    *lastExr = Clock::now();
    Film copy = f;
    try {  // a failed checkpoint (full disk) costs the safety net, not the render
      writer.write(copy, s, previous + clock.elapsed(), {firstExr(job.outputs.paths)}, false,
                   events);
    } catch (const Error& e) {
      warn(events, std::string("checkpoint not written: ") + e.what());
    }
  };
}

}  // namespace

void checkJobOutputs(const RenderJob& job) {
  ImageOutputOptions check;
  check.colorspace = job.outputs.colorspace;
  check.display = job.outputs.display, check.view = job.outputs.view;
  checkOutputs(job.outputs.paths, check);
  if (!job.outputs.aaHeatmap.empty()) checkOutputs({job.outputs.aaHeatmap}, check);
  if ((job.part.checkpointSeconds > 0 || job.part.resume) && firstExr(job.outputs.paths).empty())
    throw Error("--checkpoint and --resume need an .exr output (-o NAME.exr)");
}

LoadOptions loadOptionsOf(const RenderJob& job) {
  const RenderSettings& s = job.settings;
  LoadOptions load;
  load.scene = job.scene.index.value_or(-1);
  load.allowAnyPath = job.scene.allowAnyPath;
  load.time = animationTime(s);
  load.animation = s.getString("animation");
  load.variant = s.getString("variant");
  if (const auto shutter = shutterOf(s); shutter && load.time) {
    const float fps = s.getFloat("fps");
    load.shutterOpen = shutter->at(*load.time, fps, 0.0f);
    load.shutterClose = shutter->at(*load.time, fps, 1.0f);
    load.motionSteps = int(s.getInt("motion-steps"));
  }
  const std::vector<std::string> aovs = AovSet::parse(job.outputs.aovs);
  if (load.time && std::count(aovs.begin(), aovs.end(), "motion"))
    load.previousTime = *load.time - 1.0f / s.getFloat("fps");
  load.maxMemoryBytes = job.scene.maxMemoryBytes;
  load.textureCacheMB = job.scene.textureMemoryMB;
  load.ignoreRequiredExtensions = job.scene.ignoreRequiredExtensions;
  load.instanceArrayMin = job.scene.instanceArrayMin;
  return load;
}

std::string contentHashOf(const RenderJob& job) {
  const std::string env = job.settings.getString("env");
  return sceneContentHash(job.scene.path, job.scene.allowAnyPath,
                          env.empty() ? std::vector<std::string>{} : std::vector<std::string>{env});
}

uint64_t defaultMaxMemoryBytes() {
  FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return 0;
  unsigned long long kB = 0;
  char line[256];
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "MemTotal: %llu kB", &kB) == 1) break;
  std::fclose(f);
  return uint64_t(double(kB) / 1024.0 * 0.8 * 1048576.0);  // 80%, as --help says
}

RenderJobResult runRenderJob(const RenderJob& job, const RenderJobEvents& events,
                             const GltfDocument* document, KeptScene* kept) {
  checkJobOutputs(job);
  for (const std::string& w : unusedOptionWarnings(job.settings)) warn(events, w);
  // --threads N holds for the whole job, Embree's build included (its TBB tasks), as a user
  // sharing a machine expects: TBB takes the least of the global limits alive (Embree sets its
  // own, every core).
  std::optional<tbb::global_control> threadLimit;
  if (job.threads > 0)
    threadLimit.emplace(tbb::global_control::max_allowed_parallelism, size_t(job.threads));
  int placedCamera = -1;
  const PreparedScene scene = prepareJobScene(job, events, document, placedCamera, kept);
  enterPhase(events, "rendering");
  const auto integrator = scene.integrator(job.settings);
  const JobPlan plan = planOf(job, scene, *integrator);
  const JobWriter writer(job, outputOptionsOf(job, scene, plan.region),
                         jobSignatureOf(job, scene, placedCamera), plan.range,
                         integrator->samplesPerPixel());

  RenderJobResult result;
  result.width = scene.width(), result.height = scene.height();
  Film film(plan.region.width(), plan.region.height());
  result.pixels = size_t(film.width()) * film.height();
  RenderState state;
  RenderTime previous;
  if (job.part.resume && !resume(job, writer, scene, plan, film, state, previous, events)) {
    result.outcome = RenderJobResult::Outcome::kAlreadyFinished;
    return result;
  }
  if (events.started) events.started();
  RenderOptions options = renderOptionsOf(job, plan, events);
  const RenderClock clock;
  if (job.part.checkpointSeconds > 0 || (events.snapshot && events.snapshotSeconds > 0))
    addCheckpoints(options, job, writer, previous, clock, events);
  result.stats = renderImage(*integrator, film, state, options);
  const bool complete = !result.stats.interrupted;
  // Never a silent wrong image: samples dropped as not finite are said, even with -q.
  if (const RayStats& rays = result.stats.rays; rays.nanSamples > 0)
    warn(events, job.scene.path + ": " + std::to_string(rays.nanSamples) +
                     " sample(s) not finite were discarded (" +
                     std::to_string(rays.infiniteSamples) +
                     " infinite: radiance beyond float's range, e.g. an emitter too bright; " +
                     std::to_string(rays.nanSamples - rays.infiniteSamples) +
                     " NaN); --debug-nan says where");
  if (events.finished) events.finished(complete);

  enterPhase(events, "writing images");
  const RenderTime took = previous + result.stats.time();
  result.written = complete ? job.outputs.paths : interruptedOutputs(job.outputs.paths, events);
  if (!result.written.empty()) writer.write(film, state, took, result.written, true, events);
  if (!job.outputs.aaHeatmap.empty() && complete)
    writeImage(samplesHeatmap(film), job.outputs.aaHeatmap);
  if (job.outputs.keepImage)
    result.image = RenderJobResult::Image{std::move(film), writer.formatOf(state, took)};
  result.outcome =
      complete ? RenderJobResult::Outcome::kComplete : RenderJobResult::Outcome::kInterrupted;
  return result;
}

}  // namespace tray

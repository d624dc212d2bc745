// tray-render: the command line. Parses options into a render job (render/render_job.h), runs
// it and maps what happened to an exit code: 0 ok, 1 render error, 2 bad input or usage,
// 130 / 143 interrupted (SIGINT / SIGTERM; the image so far is written: EXRs as asked,
// PNG/JPEG under NAME.partial.EXT).
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <new>
#include <optional>
#include <set>
#include <string>

#include "cli/cli_job.h"
#include "cli/cli_options.h"
#include "cli/frames.h"
#include "cli/interrupt.h"
#include "cli/preview_server.h"
#include "cli/progress.h"
#include "core/animation_time.h"
#include "core/error.h"
#include "integrators/registry.h"
#include "io/library_threads.h"
#include "render/auto_framing.h"
#include "render/farm.h"
#include "render/render_job.h"

namespace {

/// What the job is doing, for the out-of-memory message (std::bad_alloc says nothing itself).
const char* gPhase = "starting";

/// The one line a finished render prints (unless --quiet).
void printSummary(const tray::RenderJob& job, const tray::RenderJobResult& r) {
  const tray::RenderStats& stats = r.stats;
  std::printf("%s: %dx%d, %d spp, %s on %s: %.3f s (%.3f CPU s), %.2f M rays, %.2f Mrays/s",
              job.scene.path.c_str(), r.width, r.height, int(job.settings.getInt("spp")),
              job.settings.getString("integrator").c_str(), job.accelerator.c_str(), stats.seconds,
              stats.cpuSeconds, stats.rays.total() * 1e-6, stats.mraysPerSecond());
  if (stats.rays.nanSamples)
    std::printf(", %llu NaN/Inf samples discarded", (unsigned long long)stats.rays.nanSamples);
  if (stats.passes > 0 || stats.timeLimitReached)  // a render in passes: where samples went
    std::printf("; %.1f spp on average in %d passes%s", double(stats.samples) / double(r.pixels),
                stats.passes, stats.timeLimitReached ? ", ended by --time-limit" : "");
  std::printf("\n");
}

/// The exit code of a job that ended, after its last message.
int exitCodeOf(const CliOptions& o, const tray::RenderJob& job, const tray::RenderJobResult& r) {
  using Outcome = tray::RenderJobResult::Outcome;
  if (r.outcome == Outcome::kAlreadyFinished) {
    if (!o.quiet)
      std::printf("%s: already finished: nothing to resume\n",
                  tray::firstExr(job.outputs.paths).c_str());
    return 0;
  }
  if (r.outcome == Outcome::kInterrupted) {
    const int sig = tray::interruptSignal();
    std::fprintf(stderr, "tray-render: interrupted (%s): %zu of %zu pixels done, written to %s\n",
                 sig == SIGTERM ? "SIGTERM" : "SIGINT", r.stats.pixelsDone, r.pixels,
                 r.written.front().c_str());
    return 128 + (sig ? sig : SIGINT);
  }
  if (!o.quiet) printSummary(job, r);
  return 0;
}

/// One image. `document`, when given (--frames), is the file parsed once.
int run(const CliOptions& o, const tray::RenderJob& job,
        const tray::GltfDocument* document = nullptr) {
  // First: a signal while the scene loads also stops the render (at its first pixel).
  const std::atomic<bool>& stop = tray::installInterruptHandlers();
  std::optional<tray::Progress> progress;  // its clock starts with the first tile
  tray::RenderJobEvents events;
  // Each warning once per process: --frames renders one job per frame, and a frame repeats
  // what the one before it said (the scene is unlit, an extension is ignored).
  events.warning = [](const std::string& w) {
    static std::set<std::string> said;
    if (said.insert(w).second) std::fprintf(stderr, "warning: %s\n", w.c_str());
  };
  events.phase = [](const char* phase) { gPhase = phase; };
  events.started = [&] { progress.emplace(o.progressSettings); };
  events.progress = [&](double f) {
    if (!stop.load()) progress->update(f);  // tiles cut short by a stop are not progress
  };
  events.finished = [&](bool complete) { progress->finish(complete); };
  events.stop = &stop;
  if (tray::previewPortOf(o) < 0)
    return exitCodeOf(o, job, tray::runRenderJob(job, events, document));
  // --preview: the server lives as long as the render; the job keeps its film for the last
  // snapshot.
  tray::PreviewServer preview(tray::previewPortOf(o), job.scene.path);
  std::printf("preview: http://127.0.0.1:%d/\n", preview.port());  // even with -q: it is asked for
  std::fflush(stdout);
  preview.attach(events, job);
  tray::RenderJob kept = job;
  kept.outputs.keepImage = true;
  const tray::RenderJobResult result = tray::runRenderJob(kept, events, document);
  if (result.image)
    preview.publishFinal(result.image->film, result.stats.passes > 0
                                                 ? double(result.stats.samples) / result.pixels
                                                 : job.settings.getInt("spp"));
  return exitCodeOf(o, job, result);
}

/// --frames: each frame rendered in turn from the file parsed once (tray::GltfDocument; the
/// scene, posed at the frame's time, is converted anew for each frame), with --time set to
/// frame / fps so that its job signature and EXR metadata say which time it shows. Stops at the
/// first frame that fails or is interrupted.
int runFrames(const CliOptions& o, tray::RenderJob job) {
  const tray::FrameRange range = tray::parseFrameRange(o.frames);
  const float fps = o.settings.getFloat("fps");
  auto frameJob = [&job](int64_t frame) {
    tray::RenderJob f = job;
    for (auto& path : f.outputs.paths) path = tray::framePath(path, frame);
    if (!f.outputs.aaHeatmap.empty())
      f.outputs.aaHeatmap = tray::framePath(f.outputs.aaHeatmap, frame);
    return f;
  };
  tray::checkJobOutputs(frameJob(range.first));  // the first frame's, before the file is read
  gPhase = "loading the scene";
  tray::LoadReport parseReport;
  const tray::GltfDocument document(job.scene.path, tray::loadOptionsOf(job), &parseReport);
  for (const auto& w : parseReport.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  job.scene.contentHash = tray::contentHashOf(job);  // hashed once for every frame's signature
  job.framingBounds = tray::sweptFramingBounds(job, document);  // one framing for every frame
  for (int64_t f = range.first; f <= range.last; ++f) {
    tray::RenderJob frame = frameJob(f);
    frame.settings.set("time", tray::frameTime(f, fps));
    if (!o.quiet)
      std::printf("frame %lld (time %s s): %s\n", (long long)f,
                  frame.settings.getString("time").c_str(), frame.outputs.paths.front().c_str());
    if (const int rc = run(o, frame, &document); rc != 0) return rc;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  tray::stopIdleLibraryThreads();
  CliOptions o;

  CLI::App app{"TRay: offline renderer for glTF 2.0 scenes (Embree, Whitted and path tracing)"};
  addCliOptions(app, o);

  // One line, in the form of every other error (CLI11 adds a second "Run with --help" line).
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("tray-render: error: ") + e.what() + " (see --help)\n";
  });
  try {
    app.parse(argc, argv);
    tray::checkCliOptions(o);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const tray::Error& e) {
    std::fprintf(stderr, "tray-render: error: %s\n", e.what());
    return 2;
  }
  try {
    return o.frames.empty() ? run(o, tray::jobOf(o)) : runFrames(o, tray::jobOf(o));
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

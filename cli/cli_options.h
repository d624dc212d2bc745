#pragma once
// tray-render's command line: what it holds after parsing, and the options that fill it. The
// render options (--integrator, --spp, each integrator's own) come from their declarations
// (cli/option_cli.h); these are the ones about files, threads, outputs and farm parts.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/progress.h"
#include "core/instance_array.h"
#include "core/render_options.h"

struct CliOptions {
  std::string scenePath;
  std::vector<std::string> outputs{"out.exr"};
  std::string resolution;
  std::string camera;        ///< --camera: a glTF camera index or a node/camera name; "" default
  std::optional<int> scene;  ///< --scene; none: the file's default scene
  int threads = 0;
  std::string accel = "embree";
  bool floatOutput = false;
  std::string outputColorspace;  ///< empty: the config's linear Rec.709, else scene_linear
  std::string display, view;
  bool allowAnyPath = false;
  bool ignoreRequiredExtensions = false;
  /// --instance-arrays: EXT_mesh_gpu_instancing sets of this many instances or more load as
  /// instance arrays (docs/instancing.md); 0: never.
  size_t instanceArrayMin = tray::kInstanceArrayMinInstances;
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
  std::string frames;                 ///< --frames A-B; empty: one image
  std::optional<double> maxMemoryMB;  ///< --max-memory; none: 80% of physical memory; 0: no limit
  double textureMemoryMB = 0;         ///< 0: TextureSampler::budgetFor(the scene's images)
  std::string previewPort;            ///< --preview[=PORT|any]; empty: no preview
  tray::RenderSettings settings;
};

/// Declares every tray-render option on `app`, storing into `o`.
void addCliOptions(CLI::App& app, CliOptions& o);

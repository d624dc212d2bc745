#pragma once
// A render owned by the library: what to render (RenderJob, a plain description) and the one
// route every render of a file takes (runRenderJob): scene -> default lighting -> memory check
// -> accelerator -> integrator -> film -> outputs, with checkpoints, metadata and progress.
// tray-render parses its options into a RenderJob and calls runRenderJob.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/accelerator.h"
#include "core/camera.h"
#include "core/render_options.h"
#include "core/scene.h"
#include "gltf/gltf_loader.h"
#include "io/image_output.h"
#include "render/renderer.h"

namespace tray {

/// The file to render and how to read it.
struct JobScene {
  std::string path;
  std::optional<int> index;  ///< the glTF scene; none: the file's default
  bool allowAnyPath = false;
  bool ignoreRequiredExtensions = false;
  size_t instanceArrayMin = kInstanceArrayMinInstances;  ///< LoadOptions::instanceArrayMin
  /// sceneContentHash of the file and the --env map, when known (--frames hashes it once).
  std::optional<std::string> contentHash;
  uint64_t maxMemoryBytes = 0;  ///< refuse a scene that needs more (0: no limit)
  double textureMemoryMB = 0;   ///< the texture tile budget (0: TRay's default)
};

/// What the render writes, and in which format.
struct JobOutputs {
  std::vector<std::string> paths{"out.exr"};
  bool floatOutput = false;  ///< 32-bit EXR channels instead of half
  std::string colorspace;    ///< empty: the config's linear Rec.709
  std::string display, view;
  std::string aovs;  ///< --aov's list, comma separated
  int cryptomatteRanks = 6;
  std::string aaHeatmap;  ///< an image of the samples per pixel; empty: none
  /// Keep the rendered film and its output format in the result (RenderJobResult::image):
  /// the Python module returns the pixels instead of (or besides) writing files. `paths` may
  /// then be empty: nothing is written.
  bool keepImage = false;
};

/// Farm parts and checkpoints (docs/farm.md), in the command line's spelling.
struct JobPart {
  std::string region;            ///< "x0,y0,x1,y1"; empty: the whole image
  std::string sampleRange;       ///< "a,b"; empty: every sample
  double checkpointSeconds = 0;  ///< write a checkpoint this often (0: never)
  bool resume = false;           ///< go on from the checkpoint in the first .exr output
};

/// Everything that decides one render of one file.
struct RenderJob {
  JobScene scene;
  std::string camera;      ///< a glTF camera index or a node/camera name; empty: the default
  std::string resolution;  ///< "WxH"; empty: 640 wide, the height from the camera's aspect
  std::string accelerator = "embree";
  int threads = 0;          ///< 0: every core
  RenderSettings settings;  ///< the declared options: integrator, spp, env, lens, time ...
  JobOutputs outputs;
  JobPart part;
  /// --frames: the automatic camera's bounds, swept once for every frame
  /// (render/auto_framing.h); none: each job sweeps its own when it has a --time.
  std::optional<Bounds3> framingBounds;
};

/// What the job tells its caller while it runs. Every member may be left empty.
struct RenderJobEvents {
  /// A warning (one line, without "warning: "); empty: printed on stderr.
  std::function<void(const std::string&)> warning;
  /// What the job is doing now ("loading the scene", "rendering", ...): an out-of-memory
  /// message can name it.
  std::function<void(const char*)> phase;
  /// The film is ready (resumed, when resuming): the first tile starts now.
  std::function<void()> started;
  /// The fraction of tiles done, after each tile (serialised).
  std::function<void(double)> progress;
  /// Rendering ended (complete: every pixel done), before the outputs are written.
  std::function<void(bool)> finished;
  /// When it becomes true (a signal handler), the render stops after the pixels under way and
  /// writes what it has.
  const std::atomic<bool>* stop = nullptr;
  /// Every snapshotSeconds (> 0), a copy of the film and state with the pixels done so far
  /// (a worker thread, one call at a time): the checkpoints' film copy (RenderOptions::
  /// onCheckpoint), for a live preview (cli/preview_server.h).
  std::function<void(const Film&, const RenderState&)> snapshot;
  double snapshotSeconds = 0;
};

struct RenderJobResult {
  enum class Outcome {
    kComplete,         ///< every pixel rendered and written
    kInterrupted,      ///< stopped: the pixels done are written (EXRs with the state to
                       ///< resume; PNG/JPEG under NAME.partial.EXT), see `written`
    kAlreadyFinished,  ///< --resume found the render finished: nothing done
  };
  Outcome outcome = Outcome::kComplete;
  RenderStats stats;
  int width = 0, height = 0;  ///< the whole image's
  size_t pixels = 0;          ///< the part's (region's)
  /// The files written: the outputs asked for, or for an interrupted render the EXRs and the
  /// display-referred images under NAME.partial.EXT.
  std::vector<std::string> written;
  /// JobOutputs::keepImage: the film as rendered (scene-linear, every layer) and the format
  /// and metadata its EXR outputs are written with (writeImages writes it as the job would).
  struct Image {
    Film film;
    ImageOutputOptions format;
  };
  std::optional<Image> image;
};

/// A job's scene kept between renders (the Python module's tray.Scene): read, lit and its
/// accelerator built by the first render, reused by the next ones, which may have changed
/// what the accelerator does not depend on in between: the camera, lights, material factors,
/// the environment. The scene options of later jobs (path, --scene, --env, --accel, --time,
/// memory limits) are not read again: the first job's hold.
struct KeptScene {
  std::unique_ptr<Scene> scene;  ///< null until the first render
  std::unique_ptr<Accelerator> accelerator;
  CameraDesc camera;  ///< the job's camera (--camera), before the lens options
  int placedCamera = -1;
  bool headlight = false;  ///< the default lighting was added (it follows the first camera)
};

/// Renders `job` and writes its outputs. `document`, when given (--frames), is the file parsed
/// once: the scene is converted from it at the job's time instead of reading the file again.
/// Throws tray::Error with a message for the user; output mistakes are found before the scene
/// is read, and a render stopped or failed after its first pixel keeps what it wrote.
/// `kept`, when given, holds the scene from one render to the next (see KeptScene).
RenderJobResult runRenderJob(const RenderJob& job, const RenderJobEvents& events = {},
                             const GltfDocument* document = nullptr, KeptScene* kept = nullptr);

/// Throws tray::Error for output mistakes (format, folder, colorspace, display/view, $OCIO,
/// checkpoints without an EXR): runRenderJob checks them before any work, --frames before it
/// parses the file.
void checkJobOutputs(const RenderJob& job);

/// How the job's scene is read (time, shutter, motion vectors, memory limits).
LoadOptions loadOptionsOf(const RenderJob& job);

/// The job's content hash: the scene and every file it names, and the --env map, whose pixels
/// are not in the option's value (its path).
std::string contentHashOf(const RenderJob& job);

/// --max-memory's default: 80% of the machine's memory (0, no limit, when it cannot tell).
uint64_t defaultMaxMemoryBytes();

}  // namespace tray

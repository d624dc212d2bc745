#pragma once
// Farm rendering: regions and sample ranges as the command line spells them, job signatures,
// checkpoints and resuming (docs/farm.md).
#include <optional>
#include <string>
#include <vector>

#include "core/render_options.h"
#include "film/film.h"
#include "film/render_state.h"
#include "io/image_output.h"
#include "render/image_part.h"
#include "render/render_time.h"

namespace tray {

/// Parses --region "x0,y0,x1,y1" (x1, y1 exclusive); empty: the whole width x height image.
/// Throws tray::Error (usage) unless the region is non-empty and inside the image.
PixelRegion parseRegion(const std::string& text, int width, int height);

/// Parses --sample-range "a,b" (samples a..b-1); empty: all samplesPerPixel samples ({0, 0}
/// for an integrator that places its own, adaptive). Throws tray::Error (usage) for a range
/// outside [0, samplesPerPixel) or an integrator that places its own samples.
SampleRange parseSampleRange(const std::string& text, std::optional<int> samplesPerPixel,
                             const std::string& integrator);

/// What a job renders besides its option values.
struct JobFrame {
  std::string scenePath;
  int scene = -1;
  int camera = -1;  ///< the placed camera (index into Scene::cameras); -1: framing the scene
  int width = 0, height = 0;
  std::string accelerator, aovs;
  std::string contentHash;  ///< sceneContentHash: the scene's bytes, its buffers' and images'
  std::string output;       ///< EXR precision and colorspace: "half lin_rec709"
};

/// Everything that decides the pixels of a render but its region and sample range (written as
/// "tray:job"): the frame, then "name=value" for every declared option that affects pixels
/// (render-wide, the integrator's, the wrapped integrator's), the output's precision and
/// colorspace and TRay's version. Checkpoints resume and parts merge only with their own job.
/// The scene is named by its file name and its content hash, so that machines may mount it at
/// different paths but an edited scene of the same name is another job.
std::string jobSignature(const RenderSettings& settings, const JobFrame& frame);

/// The first .exr of `outputs` (empty if none): where checkpoints go and --resume reads.
std::string firstExr(const std::vector<std::string>& outputs);

/// Loads the checkpoint at `path` for resuming: its film (AOVs of the pixels done) and state.
/// Returns false, loading nothing, when `path` is this render finished already. Throws
/// tray::Error naming the file unless its "tray:job" is `job`, its data window is `region` of a
/// width x height image and its sample range is `range`.
bool loadCheckpoint(const std::string& path, const std::string& job, const PixelRegion& region,
                    int width, int height, const SampleRange& range, Film& film, RenderState& state,
                    RenderTime& previous);

}  // namespace tray

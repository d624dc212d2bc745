#pragma once
// How a job writes its film: the final outputs and checkpoints, each with the EXR metadata
// that says what it is (tray:job, tray:status, the sample range, the options that decide its
// pixels) so that a checkpoint resumes and parts merge only with their own job.
#include <optional>
#include <string>
#include <vector>

#include "film/film.h"
#include "film/render_state.h"
#include "io/image_output.h"
#include "render/farm.h"
#include "render/prepared_scene.h"
#include "render/render_job.h"

namespace tray {

/// The job signature (tray:job) of a render of `scene`: what decides its pixels but the region
/// and sample range. `placedCamera`: findCamera's index.
std::string jobSignatureOf(const RenderJob& job, const PreparedScene& scene, int placedCamera);

/// The EXR format of the job's outputs covering `region` of `scene`'s image, with its camera
/// matrices.
ImageOutputOptions outputOptionsOf(const RenderJob& job, const PreparedScene& scene,
                                   const PixelRegion& region);

class JobWriter {
 public:
  /// `samplesPerPixel`: the integrator's (none: it places its own samples, adaptive).
  JobWriter(const RenderJob& job, ImageOutputOptions format, std::string signature,
            SampleRange range, std::optional<int> samplesPerPixel);

  const std::string& signature() const { return signature_; }

  /// The format and metadata a write of `now` after `took` of rendering carries.
  ImageOutputOptions formatOf(const RenderState& now, const RenderTime& took) const {
    return metadataOf(now, took);
  }

  /// Writes `film` (all outputs or none) with the metadata of `now`, `took` of rendering in
  /// all; the state goes with the pixels of a part or an unfinished render. `final`: the
  /// render's outputs, not a checkpoint (a half-float clamp is warned about then only).
  void write(Film& film, const RenderState& now, const RenderTime& took,
             const std::vector<std::string>& paths, bool final,
             const RenderJobEvents& events) const;

 private:
  ImageOutputOptions metadataOf(const RenderState& now, const RenderTime& took) const;

  const RenderJob& job_;
  ImageOutputOptions format_;  ///< the format and the metadata every write shares
  std::string signature_;
  SampleRange range_;
  std::optional<int> samplesPerPixel_;
  bool part_;  ///< --region or --sample-range: the state goes with the pixels
};

}  // namespace tray

#include "render/job_writer.h"

#include "core/camera_matrices.h"
#include "render/job_scene.h"
#include "render/option_metadata.h"

namespace tray {

std::string jobSignatureOf(const RenderJob& job, const PreparedScene& scene, int placedCamera) {
  const JobOutputs& out = job.outputs;
  const std::string output = std::string(out.floatOutput ? "float," : "half,") +
                             (out.colorspace.empty() ? "default" : out.colorspace);
  return jobSignature(
      job.settings,
      {job.scene.path, job.scene.index.value_or(-1), placedCamera, scene.width(), scene.height(),
       job.accelerator, out.aovs + (out.aaHeatmap.empty() ? "" : "+samples"),
       job.scene.contentHash ? *job.scene.contentHash : contentHashOf(job), output});
}

ImageOutputOptions outputOptionsOf(const RenderJob& job, const PreparedScene& scene,
                                   const PixelRegion& region) {
  ImageOutputOptions out;
  out.halfFloat = !job.outputs.floatOutput;
  out.colorspace = job.outputs.colorspace;
  out.display = job.outputs.display;
  out.view = job.outputs.view;
  out.fullWidth = scene.width(), out.fullHeight = scene.height();
  out.xOffset = region.x0, out.yOffset = region.y0;
  out.matrixMetadata = {
      {"worldToCamera", exrWorldToCamera(scene.cameraDesc())},
      {"worldToNDC", exrWorldToNdc(scene.cameraDesc(), scene.width(), scene.height())}};
  return out;
}

JobWriter::JobWriter(const RenderJob& job, ImageOutputOptions format, std::string signature,
                     SampleRange range, std::optional<int> samplesPerPixel)
    : job_(job),
      format_(std::move(format)),
      signature_(std::move(signature)),
      range_(range),
      samplesPerPixel_(samplesPerPixel),
      part_(!job.part.region.empty() || !job.part.sampleRange.empty()) {}

ImageOutputOptions JobWriter::metadataOf(const RenderState& now, const RenderTime& took) const {
  const size_t done = now.pixelsDone(), all = now.done.size();
  ImageOutputOptions w = format_;
  w.stringMetadata = {{"tray:version", TRAY_VERSION},
                      {"tray:accelerator", job_.accelerator},
                      {"tray:scene", job_.scene.path},
                      {"tray:status", done == all ? "complete" : "partial"},
                      {"tray:job", signature_}};
  // tray:samplesPerPixel 0 says "adaptive" in the file (tray-merge reads it so).
  w.floatMetadata = {{"tray:renderSeconds", float(took.seconds)},
                     {"tray:renderCpuSeconds", float(took.cpuSeconds)},
                     {"tray:pixelsDone", float(done)},
                     {"tray:pixelsTotal", float(all)},
                     {"tray:sampleBegin", float(range_.begin)},
                     {"tray:sampleEnd", float(range_.end)},
                     {"tray:samplesPerPixel", float(samplesPerPixel_.value_or(0))}};
  addOptionMetadata(job_.settings, w);  // tray:integrator, tray:spp, tray:maxDepth, ...
  if (!now.progress.empty()) {          // a render in passes: each pixel's count
    double samples = 0;
    for (const PixelProgress& g : now.progress) samples += g.count;
    w.floatMetadata.emplace_back("tray:samplesDone", float(samples));
  } else if (samplesPerPixel_) {  // adaptive: the samples AOV counts them per pixel
    w.floatMetadata.emplace_back("tray:samplesDone",
                                 float(done) * float(range_.end - range_.begin));
  }
  return w;
}

void JobWriter::write(Film& film, const RenderState& now, const RenderTime& took,
                      const std::vector<std::string>& paths, bool final,
                      const RenderJobEvents& events) const {
  if (part_ || now.pixelsDone() < now.done.size()) storeState(now, film);
  const std::vector<size_t> clamped = writeImages(film, paths, metadataOf(now, took));
  for (size_t i = 0; i < paths.size(); ++i)
    if (clamped[i] && final) warn(events, halfClampWarning(paths[i], clamped[i]));
}

}  // namespace tray

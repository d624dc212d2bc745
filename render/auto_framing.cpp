#include "render/auto_framing.h"

namespace tray {

std::optional<Bounds3> sweptFramingBounds(const RenderJob& job, const GltfDocument& document) {
  if (!job.camera.empty()) return std::nullopt;
  LoadOptions options = loadOptionsOf(job);
  const auto range = document.animationRange(options);
  if (!range || !(range->second > range->first)) return std::nullopt;
  options.geometryOnly = true;
  options.previousTime.reset();
  options.motionSteps = 0;
  Bounds3 bounds;
  for (int i = 0; i < kFramingPoses; ++i) {
    options.time = range->first + (range->second - range->first) * float(i) / (kFramingPoses - 1);
    const Scene posed = document.scene(options);
    if (!posed.cameras.empty()) return std::nullopt;  // the file places a camera: no framing
    bounds.extend(posed.bounds());
  }
  return bounds;
}

}  // namespace tray

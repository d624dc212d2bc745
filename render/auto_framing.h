#pragma once
// The automatic camera of an animated file that places none: framed once for the whole
// animation, so that a --frames sequence does not jitter and zoom as the bounds of each frame
// would make it (issue 39), and a frame rendered alone (--time, a farm task) is framed as in
// the sequence.
#include <optional>

#include "core/bounds.h"
#include "gltf/gltf_loader.h"
#include "render/render_job.h"

namespace tray {

/// Poses the sweep takes, evenly spaced from the animation's first to its last keyframe time.
/// Enough for framing, which pads the bounds anyway; not a guarantee that nothing leaves them.
constexpr int kFramingPoses = 9;

/// The scene's bounds swept over the animation `job` plays (--animation): the union of
/// kFramingPoses poses, geometry only. None when the job names a camera, the file places one,
/// or the animation has no length: the frame's own bounds are framed then.
std::optional<Bounds3> sweptFramingBounds(const RenderJob& job, const GltfDocument& document);

}  // namespace tray

#pragma once
// The job's first stages: the scene read (or converted from a parsed document), --env and the
// lens options applied, the default lighting added to an unlit scene, the memory checked and
// the accelerator built.
#include <string>

#include "render/prepared_scene.h"
#include "render/render_job.h"

namespace tray {

/// The job's scene, ready to render; `placedCamera` receives the camera's index among the
/// scene's placed cameras (findCamera; -1: one framing the scene), for the job signature.
/// Warnings and phases go to `events`. With `kept` (render/render_job.h), the scene and its
/// accelerator are kept there by the first call and borrowed from it by the next ones.
PreparedScene prepareJobScene(const RenderJob& job, const RenderJobEvents& events,
                              const GltfDocument* document, int& placedCamera,
                              KeptScene* kept = nullptr);

/// Reports a warning through `events` (stderr when it has no handler).
void warn(const RenderJobEvents& events, const std::string& message);
/// Reports the job's phase through `events`.
void enterPhase(const RenderJobEvents& events, const char* phase);

}  // namespace tray

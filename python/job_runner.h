#pragma once
// Runs a render job for Python: the render on a thread of its own with the GIL released, while
// the calling (main) thread waits, calls the progress callback with the fraction done, turns
// the job's warnings into Python warnings and checks for signals. Ctrl-C (KeyboardInterrupt)
// or an exception from the callback sets the job's stop flag: the render stops after the
// pixels under way, writes what it asked to write, and the exception is raised then.
#include <pybind11/pybind11.h>

#include "cli/preview_server.h"
#include "render/render_job.h"

namespace tray::python {

/// `progress`: None or a callable taking the fraction of the image done (0..1); it is called
/// on the calling thread, each time the fraction has changed, at most every 50 ms and once
/// with the last fraction. `kept`: runRenderJob's. `setupSeconds`, when given, receives the
/// time from the call to the first tile (reading the scene, building the accelerator).
/// `preview`, when given, shows the render (--preview; the job must keep its image). Throws
/// what runRenderJob throws, or the Python error that stopped the render.
RenderJobResult runJob(const RenderJob& job, const pybind11::object& progress,
                       const GltfDocument* document = nullptr, KeptScene* kept = nullptr,
                       double* setupSeconds = nullptr, PreviewServer* preview = nullptr);

}  // namespace tray::python

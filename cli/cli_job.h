#pragma once
// From a parsed command line to a render job: the checks parsing alone cannot make, and the
// job the options describe. tray-render and the Python module (python/) share them, so that
// both refuse the same input with the same message and render the same job.
#include "cli/cli_options.h"
#include "render/render_job.h"

namespace tray {

/// Checks what parsing alone cannot: option ranges, --time, --frames and --shutter together,
/// output patterns and --progress. Throws tray::Error.
void checkCliOptions(CliOptions& o);

/// --preview's port: -1 none, 0 any free port.
int previewPortOf(const CliOptions& o);

/// The render job the options describe (one image; --frames makes one per frame).
RenderJob jobOf(const CliOptions& o);

}  // namespace tray

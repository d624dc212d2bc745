#pragma once
// tray.Image: a rendered film as NumPy arrays (views of its layers), the metadata its EXR
// carries, and write(), which writes it as tray-render writes its outputs (io/image_output.h).
#include <pybind11/pybind11.h>

#include <string>

#include "render/render_job.h"

namespace tray::python {

struct Image {
  Film film;
  ImageOutputOptions format;  ///< the job's output format and metadata (JobWriter)
  RenderStats stats;
  bool complete = true;
  double setupSeconds = 0;  ///< from the call to the first tile: loading, building
};

/// The Image of a job run with JobOutputs::keepImage.
Image imageOf(RenderJobResult&& result, double setupSeconds);

/// Binds tray.Image and tray.RenderStats in `m`.
void bindImage(pybind11::module_& m);

}  // namespace tray::python

#pragma once
// tray.Scene: a scene read once and rendered many times, edited in between (the camera, light
// intensities, the environment's rotation and intensity, material factors). Its accelerator is
// built once, by the load: none of these edits changes the geometry it is built over
// (render/render_job.h, KeptScene).
#include <pybind11/pybind11.h>

namespace tray::python {

/// Binds tray._tray.Scene in `m` (python/tray/__init__.py wraps it as tray.Scene).
void bindScene(pybind11::module_& m);

}  // namespace tray::python

// The tray Python module's native part (_tray): the command line's option table and checks
// (cli/cli_options.h, cli/cli_job.h) read from an argument list the Python side makes of its
// keywords, the render job run with progress and Ctrl-C (python/job_runner.h), and the film
// returned as tray.Image (python/image.h). python/tray/__init__.py is the public face.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/cli_job.h"
#include "cli/cli_options.h"
#include "cli/frames.h"
#include "core/animation_time.h"
#include "core/error.h"
#include "python/image.h"
#include "python/job_runner.h"
#include "python/options.h"
#include "python/scene.h"

namespace py = pybind11;

namespace tray::python {
namespace {

/// One image; with --preview (`previewPort` >= 0) shown live on localhost as tray-render
/// shows it.
Image renderOne(const RenderJob& job, const py::object& progress, int previewPort,
                const GltfDocument* document = nullptr) {
  std::optional<PreviewServer> preview;
  if (previewPort >= 0) {
    preview.emplace(previewPort, job.scene.path);
    const std::string line = "preview: http://127.0.0.1:" + std::to_string(preview->port()) + "/";
    py::print(line, py::arg("flush") = true);
  }
  double setup = 0;
  RenderJobResult result =
      runJob(job, progress, document, nullptr, &setup, preview ? &*preview : nullptr);
  return imageOf(std::move(result), setup);
}

/// render(args, progress): one Image, or with --frames a list of them, frame by frame as
/// tray-render --frames renders them (the file parsed once, each frame at frame / fps).
py::object render(const std::vector<std::string>& args, const py::object& progress) {
  CliOptions o = parseOptions(args);
  RenderJob job = jobOf(o);
  job.outputs.keepImage = true;
  if (o.frames.empty()) return py::cast(renderOne(job, progress, previewPortOf(o)));
  const FrameRange range = parseFrameRange(o.frames);
  std::unique_ptr<GltfDocument> document;
  {
    py::gil_scoped_release release;
    document = std::make_unique<GltfDocument>(job.scene.path, loadOptionsOf(job));
    job.scene.contentHash = contentHashOf(job);
  }
  py::list frames;
  for (int64_t f = range.first; f <= range.last; ++f) {
    RenderJob frame = job;
    for (auto& path : frame.outputs.paths) path = framePath(path, f);
    if (!frame.outputs.aaHeatmap.empty())
      frame.outputs.aaHeatmap = framePath(frame.outputs.aaHeatmap, f);
    frame.settings.set("time", frameTime(f, o.settings.getFloat("fps")));
    frames.append(py::cast(renderOne(frame, progress, previewPortOf(o), document.get())));
  }
  return frames;
}

}  // namespace
}  // namespace tray::python

PYBIND11_MODULE(_tray, m) {
  using namespace tray::python;
  m.doc() = "TRay's native module; use the tray package (docs/python.md)";
  py::register_exception<tray::Error>(m, "Error");
  bindImage(m);
  bindScene(m);
  m.def("render", &render, py::arg("args"), py::arg("progress") = py::none(),
        "Renders tray-render's command line `args` (without the program name)");
  m.def("check", [](const std::vector<std::string>& args) { parseOptions(args); },
        py::arg("args"), "Checks tray-render's command line `args` as render() would");
  m.def("option_names", &optionNames, "tray-render's long option names, '_' for '-'");
  m.attr("__version__") = TRAY_VERSION;
}

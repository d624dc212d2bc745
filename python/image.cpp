#include "python/image.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "core/error.h"
#include "io/image_output.h"

namespace py = pybind11;

namespace tray::python {
namespace {

/// A layer's pixels as an H x W x C float32 array viewing the film (no copy): it keeps the
/// Image alive, and writing into it changes what write() writes.
py::array layerArray(py::object self, const FilmLayer& layer, int width, int height) {
  const auto c = py::ssize_t(layer.channels.size());
  const auto f = py::ssize_t(sizeof(float));
  return py::array_t<float>({py::ssize_t(height), py::ssize_t(width), c},
                            {f * c * width, f * c, f}, layer.data.data(), self);
}

/// The name Python uses for a layer: the beauty's is empty in the film.
std::string layerName(const FilmLayer& layer) { return layer.name.empty() ? "beauty" : layer.name; }

py::dict metadataOf(const Image& image) {
  py::dict d;
  for (const auto& [key, value] : image.format.stringMetadata) d[key.c_str()] = value;
  for (const auto& [key, value] : image.format.floatMetadata) d[key.c_str()] = value;
  for (const auto& [key, m] : image.format.matrixMetadata) {
    py::array_t<float> a({4, 4});
    std::copy(m.begin(), m.end(), a.mutable_data());
    d[key.c_str()] = a;
  }
  for (const auto& [key, value] : image.film.metadata()) d[key.c_str()] = value;
  return d;
}

/// write(path, float=None): as tray-render writes an output (all layers to EXR, the beauty
/// through the display view to PNG/JPEG); `float` overrides the render's --float.
void write(const Image& image, const std::filesystem::path& file,
           std::optional<bool> floatOutput) {
  const std::string path = file.string();
  ImageOutputOptions format = image.format;
  if (floatOutput) format.halfFloat = !*floatOutput;
  checkOutputs({path}, format);
  const std::vector<size_t> clamped = writeImages(image.film, {path}, format);
  if (clamped[0])
    if (PyErr_WarnEx(PyExc_UserWarning, halfClampWarning(path, clamped[0]).c_str(), 1) != 0)
      throw py::error_already_set();
}

}  // namespace

Image imageOf(RenderJobResult&& result, double setupSeconds) {
  return Image{std::move(result.image->film), std::move(result.image->format), result.stats,
               result.outcome == RenderJobResult::Outcome::kComplete, setupSeconds};
}

void bindImage(py::module_& m) {
  py::class_<RenderStats>(m, "RenderStats", "What a render did: time, rays, samples.")
      .def_readonly("seconds", &RenderStats::seconds)
      .def_readonly("interrupted", &RenderStats::interrupted)
      .def_readonly("pixels_done", &RenderStats::pixelsDone)
      .def_readonly("passes", &RenderStats::passes)
      .def_readonly("samples", &RenderStats::samples)
      .def_readonly("time_limit_reached", &RenderStats::timeLimitReached)
      .def_property_readonly("rays", [](const RenderStats& s) { return s.rays.total(); })
      .def_property_readonly("mrays_per_second", &RenderStats::mraysPerSecond);

  py::class_<Image>(m, "Image", "A rendered image: tray.render's result.")
      .def_property_readonly("width", [](const Image& i) { return i.film.width(); })
      .def_property_readonly("height", [](const Image& i) { return i.film.height(); })
      .def_property_readonly(
          "beauty",
          [](py::object self) {
            const Image& i = self.cast<const Image&>();
            return layerArray(self, i.film.layers()[Film::kBeauty], i.film.width(),
                              i.film.height());
          },
          "H x W x 4 float32: scene-linear RGB and alpha, as the film holds it")
      .def_property_readonly(
          "aovs",
          [](py::object self) {
            const Image& i = self.cast<const Image&>();
            py::dict d;
            for (const FilmLayer& l : i.film.layers())
              if (!l.name.empty())
                d[l.name.c_str()] = layerArray(self, l, i.film.width(), i.film.height());
            return d;
          },
          "the AOV layers by name, each H x W x C float32 (channels in .channels[name])")
      .def_property_readonly(
          "channels",
          [](const Image& i) {
            py::dict d;
            for (const FilmLayer& l : i.film.layers()) d[layerName(l).c_str()] = l.channels;
            return d;
          },
          "each layer's channel names in array order ('beauty': R, G, B, A)")
      .def_property_readonly(
          "exr_channels",
          [](const Image& i) {
            py::dict d;
            for (const FilmLayer& l : i.film.layers()) {
              std::vector<std::string> names;
              for (const auto& c : l.channels) names.push_back(exrChannelName(l, c));
              d[layerName(l).c_str()] = names;
            }
            return d;
          },
          "each layer's channel names as its EXR output names them (N.X, Z, ...)")
      .def_property_readonly("metadata", &metadataOf,
                             "the header attributes the EXR output carries (tray:*, matrices)")
      .def_property_readonly("stats", [](const Image& i) { return i.stats; })
      .def_property_readonly(
          "setup_seconds", [](const Image& i) { return i.setupSeconds; },
          "seconds from the call to the first tile: reading the scene, building the accelerator")
      .def_property_readonly("complete", [](const Image& i) { return i.complete; },
                             "False: the render was stopped (tray:status partial)")
      .def(
          "to_display",
          [](const Image& i, const std::string& layer, const std::string& display,
             const std::string& view) {
            const int index = i.film.findLayer(layer == "beauty" ? "" : layer);
            if (index < 0) throw Error(layer + ": no such layer in this image");
            const std::vector<unsigned char> bytes = displayBytes(
                i.film, index, display.empty() ? i.format.display : display,
                view.empty() ? i.format.view : view);
            py::array_t<uint8_t> a({i.film.height(), i.film.width(), 3});
            std::copy(bytes.begin(), bytes.end(), a.mutable_data());
            return a;
          },
          py::arg("layer") = "beauty", py::arg("display") = "", py::arg("view") = "",
          "H x W x 3 uint8: the layer as a PNG output shows it (OCIO display/view; default "
          "the render's display and view options)")
      .def("write", &write, py::arg("path"), py::arg("float") = py::none(),
           "Writes the image as tray-render writes -o PATH: .exr (every layer, scene-linear; "
           "half unless float=True or the render's float=True) or .png/.jpg (display-referred)")
      .def("__repr__", [](const Image& i) {
        return "<tray.Image " + std::to_string(i.film.width()) + "x" +
               std::to_string(i.film.height()) + ", " + std::to_string(i.film.layers().size()) +
               " layers>";
      });
}

}  // namespace tray::python

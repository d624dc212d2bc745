#include "python/scene.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "cli/cli_job.h"
#include "core/error.h"
#include "python/image.h"
#include "python/job_runner.h"
#include "python/options.h"
#include "render/job_scene.h"

namespace py = pybind11;

namespace tray::python {
namespace {

Color colorOf(const std::vector<float>& v, const char* what) {
  if (v.size() != 3 && v.size() != 4)
    throw Error(std::string(what) + ": expected 3 values (RGB), got " + std::to_string(v.size()));
  for (float c : v)
    if (!std::isfinite(c) || c < 0)
      throw Error(std::string(what) + ": expected finite values >= 0");
  return Color(v[0], v[1], v[2]);
}

std::vector<float> listOf(const Color& c) { return {c.x, c.y, c.z}; }

float checked(float v, float lo, float hi, const char* what) {
  if (!std::isfinite(v) || v < lo || v > hi)
    throw Error(std::string(what) + ": expected a finite number in [" + std::to_string(lo) +
                ", " + std::to_string(hi) + "]");
  return v;
}

class SceneHandle {
 public:
  /// Reads the scene tray-render's `args` name, lights it as a render would and builds its
  /// accelerator.
  explicit SceneHandle(const std::vector<std::string>& args) {
    const RenderJob job = jobOf(parseOptions(args));
    std::vector<std::string> warnings;
    RenderJobEvents events;
    events.warning = [&warnings](const std::string& w) { warnings.push_back(w); };
    const auto start = std::chrono::steady_clock::now();
    {
      py::gil_scoped_release release;
      int placed = -1;
      prepareJobScene(job, events, nullptr, placed, &kept_);
      // The job signature (tray:job) hashes the file and every file it names: once here,
      // not at every render (edits are not in it; the file's content is).
      contentHash_ = contentHashOf(job);
    }
    loadSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (const std::string& w : warnings)
      if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) throw py::error_already_set();
  }

  Image render(const std::vector<std::string>& args, const py::object& progress) {
    const CliOptions o = parseOptions(args);
    RenderJob job = jobOf(o);
    job.outputs.keepImage = true;
    job.scene.contentHash = contentHash_;
    std::optional<PreviewServer> preview;
    if (previewPortOf(o) >= 0) preview.emplace(previewPortOf(o), job.scene.path);
    double setup = 0;
    RenderJobResult result =
        runJob(job, progress, nullptr, &kept_, &setup, preview ? &*preview : nullptr);
    return imageOf(std::move(result), setup);
  }

  double loadSeconds() const { return loadSeconds_; }
  Scene& scene() { return *kept_.scene; }
  CameraDesc& camera() { return kept_.camera; }

  PunctualLightDesc& light(size_t i) {
    if (i >= scene().lights.size()) throw py::index_error("no light " + std::to_string(i));
    return scene().lights[i];
  }
  Material& material(size_t i) {
    if (i >= scene().materials.size()) throw py::index_error("no material " + std::to_string(i));
    return scene().materials[i];
  }

 private:
  KeptScene kept_;
  std::string contentHash_;
  double loadSeconds_ = 0;
};

py::array_t<float> matrixArray(const Mat4& m) {
  py::array_t<float> a({4, 4});
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) a.mutable_at(r, c) = m.m[r][c];
  return a;
}

void setCameraToWorld(SceneHandle& s, const py::array_t<float, py::array::forcecast>& a) {
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
    throw Error("camera_to_world: expected a 4 x 4 matrix");
  Mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.m[r][c] = a.at(r, c);
  CameraDesc& camera = s.camera();
  camera.toWorld = Transform(m);  // throws tray::Error when singular or not finite
  camera.motion.clear();          // a posed camera holds still
  camera.previousToWorld.reset();
}

py::dict lightDict(const PunctualLightDesc& l) {
  static const char* kTypes[] = {"point", "spot", "directional"};
  py::dict d;
  d["type"] = kTypes[int(l.type)];
  d["intensity"] = listOf(l.intensity);
  d["position"] = listOf(l.position);
  d["direction"] = listOf(l.direction);
  return d;
}

py::dict materialDict(const Material& m) {
  py::dict d;
  d["name"] = m.name;
  d["base_color"] = listOf(m.baseColor);
  d["metallic"] = m.metallic;
  d["roughness"] = m.roughness;
  d["emissive"] = listOf(m.emissive);
  d["transmission"] = m.transmission;
  d["ior"] = m.ior;
  return d;
}

/// Sets the factors given (None: unchanged). Textures multiply them, as in glTF.
void setMaterial(Material& m, std::optional<std::vector<float>> baseColor,
                 std::optional<float> metallic, std::optional<float> roughness,
                 std::optional<std::vector<float>> emissive, std::optional<float> transmission,
                 std::optional<float> ior) {
  Material edited = m;  // all or nothing: a bad value leaves the material as it was
  if (baseColor) edited.baseColor = colorOf(*baseColor, "base_color");
  if (metallic) edited.metallic = checked(*metallic, 0, 1, "metallic");
  if (roughness) edited.roughness = checked(*roughness, 0, 1, "roughness");
  if (emissive) edited.emissive = colorOf(*emissive, "emissive");
  if (transmission) edited.transmission = checked(*transmission, 0, 1, "transmission");
  if (ior) edited.ior = checked(*ior, 1, 10, "ior");
  m = edited;
}

}  // namespace

void bindScene(py::module_& m) {
  py::class_<SceneHandle>(m, "Scene", "A scene read once; see tray.Scene")
      .def(py::init<const std::vector<std::string>&>(), py::arg("args"))
      .def("render", &SceneHandle::render, py::arg("args"), py::arg("progress") = py::none())
      .def_property_readonly("load_seconds", &SceneHandle::loadSeconds)
      .def_property(
          "camera_to_world", [](SceneHandle& s) { return matrixArray(s.camera().toWorld.m); },
          &setCameraToWorld)
      .def_property(
          "yfov", [](SceneHandle& s) { return s.camera().yfov; },
          [](SceneHandle& s, float v) { s.camera().yfov = checked(v, 1e-4f, 3.14f, "fov"); })
      .def_property_readonly("lights",
                             [](SceneHandle& s) {
                               py::list l;
                               for (const auto& light : s.scene().lights) l.append(lightDict(light));
                               return l;
                             })
      .def("set_light_intensity",
           [](SceneHandle& s, size_t i, const std::vector<float>& rgb) {
             s.light(i).intensity = colorOf(rgb, "intensity");
           })
      .def_property_readonly("materials",
                             [](SceneHandle& s) {
                               py::list l;
                               for (const auto& mat : s.scene().materials)
                                 l.append(materialDict(mat));
                               return l;
                             })
      .def(
          "set_material",
          [](SceneHandle& s, size_t i, std::optional<std::vector<float>> baseColor,
             std::optional<float> metallic, std::optional<float> roughness,
             std::optional<std::vector<float>> emissive, std::optional<float> transmission,
             std::optional<float> ior) {
            setMaterial(s.material(i), baseColor, metallic, roughness, emissive, transmission,
                        ior);
          },
          py::arg("index"), py::arg("base_color") = py::none(), py::arg("metallic") = py::none(),
          py::arg("roughness") = py::none(), py::arg("emissive") = py::none(),
          py::arg("transmission") = py::none(), py::arg("ior") = py::none())
      .def_property(
          "environment_rotation", [](SceneHandle& s) { return s.scene().environment.rotation; },
          [](SceneHandle& s, float v) {
            s.scene().environment.rotation = checked(v, -1e6f, 1e6f, "environment_rotation");
          })
      .def_property(
          "environment_intensity",
          [](SceneHandle& s) { return s.scene().environment.intensity; },
          [](SceneHandle& s, float v) {
            s.scene().environment.intensity = checked(v, 0, 1e9f, "environment_intensity");
          })
      .def_property(
          "background", [](SceneHandle& s) { return listOf(s.scene().environment.background); },
          [](SceneHandle& s, const std::vector<float>& rgb) {
            s.scene().environment.background = colorOf(rgb, "background");
          });
}

}  // namespace tray::python

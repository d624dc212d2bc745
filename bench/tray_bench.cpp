// tray-bench: speed against accuracy. `tray-bench sweep SCENE` renders the scene with every
// registered method and setting, measures wall time, rays and error against a converged
// reference, and writes CSV for tools/plot_bench.py (charts + Pareto report).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "accel/registry.h"
#include "bench/cpu_time.h"
#include "bench/image_error.h"
#include "bench/sweep.h"
#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "io/image_output.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"

namespace fs = std::filesystem;
using namespace tray;

namespace {

/// The scene prepared once per accelerator.
struct Bench {
  const Scene& scene;
  CameraDesc camera;
  ImageSize size;
  std::map<std::string, PreparedScene> prepared;
  /// CPU seconds of the last render (every thread's): per CPU-second figures stay comparable
  /// when other work shares the machine.
  double lastCpuSeconds = 0;

  std::pair<Film, RenderStats> render(const RenderSettings& s, const std::string& accelName,
                                      int threads, const std::vector<std::string>& aovs = {}) {
    const PreparedScene& p =
        prepared.try_emplace(accelName, scene, camera, size, accelName).first->second;
    auto integrator = p.integrator(s);
    Film film(size.width, size.height);
    RenderOptions opt;
    opt.threads = threads;
    opt.aovs = aovs;
    opt.passes = samplingPassesOf(integrator->context().settings);
    const double cpu = cpuSeconds();
    RenderStats st = renderImage(*integrator, film, opt);
    lastCpuSeconds = cpuSeconds() - cpu;
    return {std::move(film), st};
  }
};

/// `film` (beauty, albedo, normal) denoised by tools/tray-denoise (docs/denoising.md), and the
/// wall seconds the tool took, start-up included: what a user pays for it.
std::pair<Film, double> denoise(const Film& film, const std::string& tool, const std::string& dir) {
  const std::string in = dir + "/denoise-in.exr", out = dir + "/denoise-out.exr";
  ImageOutputOptions o;
  o.halfFloat = false;
  writeImage(film, in, o);
  const auto start = std::chrono::steady_clock::now();
  const std::string command = "'" + tool + "' '" + in + "' -o '" + out + "'";
  if (std::system(command.c_str()) != 0) throw Error("denoising failed: " + command);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {readReference(out), seconds};
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

int sweep(const std::string& scenePath, const std::string& resolution, const std::string& outDir,
          const std::string& referenceFile, int referenceSpp, int maxSpp,
          const std::string& accelList, const std::string& threadList, const std::string& denoiser,
          const std::string& methodList) {
  LoadOptions load;
  load.allowAnyPath = true;  // scenes/bench/ take their assets from ../shared
  Scene scene = loadGltf(scenePath, load);
  scene.sourcePath = scenePath;
  CameraDesc cd = chooseCamera(scene, -1);
  ImageSize size = resolveImageSize(resolution, cd);
  Bench bench{scene, cd, size, {}};
  fs::create_directories(outDir);
  const std::string stem = fs::path(scenePath).stem().string();

  // One converged reference per integrator family, cached beside the CSV.
  std::map<std::string, Film> references;
  auto reference = [&](const std::string& integrator) -> const Film& {
    std::string family = integrator == "path" ? "path" : "whitted";
    auto it = references.find(family);
    if (it != references.end()) return it->second;
    const std::string path =
        !referenceFile.empty() ? referenceFile
                               : referencePath(outDir, scenePath, family, size.width, size.height);
    if (!fs::exists(path)) {
      std::fprintf(stderr, "tray-bench: rendering the %s reference to %s\n", family.c_str(),
                   path.c_str());
      auto [film, st] = bench.render(referenceSettings(family, referenceSpp), "embree", 0);
      ImageOutputOptions o;
      o.halfFloat = false;
      writeImage(film, path, o);
    }
    Film film = readReferenceOfSize(path, size.width, size.height);
    return references.emplace(family, std::move(film)).first->second;
  };

  std::vector<int> threads;
  for (const auto& t : splitList(threadList)) threads.push_back(std::stoi(t));
  std::string csvPath = outDir + "/" + stem + ".csv";
  std::ofstream csv(csvPath);
  csv << "scene,method,setting,integrator,accel,threads,spp,seconds,rays,rmse,relmse,bias,max_"
         "abs,cpu_seconds,relmse_trimmed\n";
  std::printf("%-34s %-16s %9s %10s %10s %10s %10s\n", "method", "setting", "seconds", "Mrays",
              "RMSE", "relMSE", "bias");
  auto record = [&](const SweepConfig& c, const std::string& method, const RenderStats& st,
                    double seconds, const ImageError& e) {
    std::printf("%-34s %-16s %9.3f %10.3f %10.3e %10.3e %+10.2e\n", method.c_str(),
                c.setting.c_str(), seconds, st.rays.total() * 1e-6, e.rmse, e.relMse, e.bias);
    std::fflush(stdout);
    csv << stem << ',' << method << ',' << c.setting << ',' << c.settings.getString("integrator")
        << ',' << c.accel << ',' << c.threads << ',' << c.settings.getInt("spp") << ',' << seconds
        << ',' << st.rays.total() << ',' << e.rmse << ',' << e.relMse << ',' << e.bias << ','
        << e.maxAbs << ',' << bench.lastCpuSeconds << ',' << e.relMseTrimmed << '\n';
  };
  const std::vector<std::string> methods = splitList(methodList);
  for (const SweepConfig& c : standardSweep(splitList(accelList), threads, maxSpp)) {
    if (!methods.empty() && std::find(methods.begin(), methods.end(), c.method) == methods.end())
      continue;
    const std::string integrator = c.settings.getString("integrator");
    const Film& ref =
        reference(integrator == "adaptive" ? c.settings.getString("inner") : integrator);
    auto [film, st] = bench.render(c.settings, c.accel, c.threads);
    record(c, c.method, st, st.seconds, compareBeauty(film, ref));
    // --denoise: the Sobol' path tracer again with the all-sample albedo and normal, then Open
    // Image Denoise; its time is the render's plus the tool's.
    if (denoiser.empty() || c.method.rfind("path sobol", 0) != 0) continue;
    auto [aux, auxStats] = bench.render(c.settings, c.accel, c.threads, {"albedo", "normal"});
    auto [clean, denoiseSeconds] = denoise(aux, denoiser, outDir);
    std::string method = c.method;
    method.insert(std::string("path sobol").size(), " + OIDN");
    record(c, method, auxStats, auxStats.seconds + denoiseSeconds, compareBeauty(clean, ref));
  }
  if (!denoiser.empty())
    for (const char* f : {"/denoise-in.exr", "/denoise-out.exr"}) fs::remove(outDir + f);
  std::printf("wrote %s (chart and Pareto report: tools/plot_bench.py %s)\n", csvPath.c_str(),
              csvPath.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tray-bench: speed against accuracy for TRay's methods"};
  app.require_subcommand(1);
  auto* sw = app.add_subcommand("sweep", "sweep methods and settings over one scene");
  std::string scene, resolution = "320x240", out = "bench-out", reference, accels = "embree",
                     threads = "0";
  int referenceSpp = 4096, maxSpp = 1024;
  sw->add_option("scene", scene, "glTF scene")->required();
  sw->add_option("--resolution", resolution, "image size WxH")->capture_default_str();
  sw->add_option("--out", out, "output folder for CSV and cached references")
      ->capture_default_str();
  sw->add_option("--reference", reference,
                 "converged reference EXR (default: rendered and cached)");
  sw->add_option("--reference-spp", referenceSpp, "spp of a rendered path reference")
      ->capture_default_str();
  sw->add_option("--max-spp", maxSpp, "largest spp swept")->capture_default_str();
  sw->add_option("--accels", accels, "comma-separated accelerators")->capture_default_str();
  sw->add_option("--threads", threads, "comma-separated thread counts (0 = all)")
      ->capture_default_str();
  bool withDenoiser = false;
  std::string denoiser = std::string(TRAY_SOURCE_DIR) + "/tools/tray-denoise";
  sw->add_flag("--denoise", withDenoiser,
               "also denoise the Sobol' path renders (lines 'path sobol + OIDN', "
               "docs/denoising.md)");
  sw->add_option("--denoiser", denoiser, "the tray-denoise to run")->capture_default_str();
  std::string methods;
  sw->add_option("--methods", methods,
                 "comma-separated methods to run (e.g. \"path sobol,path sobol adaptive\"; "
                 "default: all)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return sweep(scene, resolution, out, reference, referenceSpp, maxSpp, accels, threads,
                 withDenoiser ? denoiser : "", methods);
  } catch (const Error& e) {
    std::fprintf(stderr, "tray-bench: error: %s\n", e.what());
    return e.kind() == Error::Kind::kInput ? 2 : 1;
  }
}

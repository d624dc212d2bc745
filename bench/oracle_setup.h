#pragma once
// The settings both oracle benches take (adaptive_oracle, adaptive_cost_oracle): the scene, the
// image, the pools of independent renders and the budgets compared, declared once for both.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "render/render_setup.h"
#include "bench/sweep.h"

namespace tray {

struct OracleSetup {
  std::string scene, resolution = "320x240", out = "bench-out", reference,
                     budgets = "32,64,128,256";
  int seeds = 128, spp = 16, maxSpp = 1024, threads = 0;
};

/// An oracle bench's scene, loaded as tray-bench's sweep loads it: the file's first camera (or
/// the automatic one) at --resolution.
struct OracleScene {
  Scene scene;
  CameraDesc camera;
  ImageSize size;
};

inline OracleScene loadOracleScene(const OracleSetup& o) {
  LoadOptions load;
  load.allowAnyPath = true;  // the benchmark scenes take their assets from ../shared
  OracleScene s{loadGltf(o.scene, load), {}, {}};
  s.scene.sourcePath = o.scene;
  s.camera = chooseCamera(s.scene, -1);
  s.size = resolveImageSize(o.resolution, s.camera);
  return s;
}

/// The reference both oracle benches measure against: --reference, else the sweep's cached
/// path reference of the scene at this size in --out (adaptive_oracle renders it if missing).
inline std::string oracleReferencePath(const OracleSetup& o, const ImageSize& size) {
  return o.reference.empty() ? referencePath(o.out, o.scene, "path", size.width, size.height)
                             : o.reference;
}

/// The options of OracleSetup's fields, in the order both tools list them (--out, --reference
/// and --threads last, after a tool's own).
inline void addOracleOptions(CLI::App& app, OracleSetup& o) {
  app.add_option("scene", o.scene, "glTF scene")->required();
  app.add_option("--resolution", o.resolution, "image size WxH")->capture_default_str();
  app.add_option("--seeds", o.seeds, "independent renders (half for variances, half spent)")
      ->capture_default_str();
  app.add_option("--spp", o.spp, "samples of each render: one step")->capture_default_str();
  app.add_option("--budgets", o.budgets, "mean spp compared, multiples of --spp")
      ->capture_default_str();
  app.add_option("--max-spp", o.maxSpp, "most samples a pixel may take")->capture_default_str();
}

inline void addOracleOutputOptions(CLI::App& app, OracleSetup& o) {
  app.add_option("--out", o.out, "folder of the cached reference")->capture_default_str();
  app.add_option("--reference", o.reference, "converged reference EXR");
  app.add_option("--threads", o.threads, "threads (0 = all)")->capture_default_str();
}

/// Parses the command line and runs `run`: exit 2 on a bad option (CLI11's message), 1 with
/// "NAME: error: ..." on a renderer error.
template <class Run>
int runOracleTool(CLI::App& app, int argc, char** argv, const char* name, Run&& run) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    return run();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", name, e.what());
    return 1;
  }
}

}  // namespace tray

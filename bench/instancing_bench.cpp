// instancing_bench: what EXT_mesh_gpu_instancing instances cost (docs/instancing.md). Loads a
// scene (tools/make_instancing_scene.py --count N writes one), builds the accelerator and
// renders, printing after each phase the resident set (VmRSS, and the peak VmHWM) and the
// phase's wall and CPU seconds, and sizeof(Primitive) (what each instance costs in the Scene).
// bench/instancing_bench.py runs it and tray-render under /usr/bin/time -v for 10^3 and 10^6
// instances. Usage: instancing_bench scene.gltf [embree|bvh] [WxH] [spp] [integrator]
// [instance-array-min] (LoadOptions::instanceArrayMin, tray-render --instance-arrays; 0: none)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "accel/registry.h"
#include "bench/cpu_time.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"

using namespace tray;

namespace {

/// A field of /proc/self/status in MiB (VmRSS, VmHWM).
double statusMiB(const char* field) {
  std::ifstream f("/proc/self/status");
  std::string key;
  while (f >> key) {
    if (key == std::string(field) + ":") {
      double kb = 0;
      f >> kb;
      return kb / 1024.0;
    }
    std::getline(f, key);
  }
  return 0;
}

struct Phase {
  const char* name;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  double cpu0 = cpuSeconds();
  ~Phase() {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-8s wall %8.3f s  cpu %8.3f s  rss %8.1f MiB  peak %8.1f MiB\n", name, wall,
                cpuSeconds() - cpu0, statusMiB("VmRSS"), statusMiB("VmHWM"));
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s scene.gltf [embree|bvh] [WxH] [spp] [integrator] [array-min]\n",
                 argv[0]);
    return 2;
  }
  const std::string accel = argc > 2 ? argv[2] : "embree";
  int w = 256, h = 256;
  if (argc > 3) std::sscanf(argv[3], "%dx%d", &w, &h);
  const int spp = argc > 4 ? std::atoi(argv[4]) : 4;
  const std::string integrator = argc > 5 ? argv[5] : "whitted";
  std::printf("sizeof(Primitive) %zu bytes, sizeof(Transform) %zu\n", sizeof(Primitive),
              sizeof(Transform));
  {
    Phase p{"start"};
  }
  Scene scene;
  {
    Phase p{"load"};
    LoadOptions o;
    o.allowAnyPath = true;
    if (argc > 6) o.instanceArrayMin = size_t(std::atoll(argv[6]));
    scene = loadGltf(argv[1], o);
  }
  size_t triangles = 0, vertices = 0;
  for (const auto& m : scene.meshes) triangles += m.triangleCount(), vertices += m.positions.size();
  std::printf("%zu primitives over %zu meshes (%zu triangles, %zu vertices)\n",
              scene.primitives.size(), scene.meshes.size(), triangles, vertices);
  const CameraDesc cam = chooseCamera(scene, -1);
  std::unique_ptr<PreparedScene> prepared;
  {
    Phase p{"build"};
    prepared = std::make_unique<PreparedScene>(scene, cam, ImageSize{w, h}, accel);
  }
  RenderSettings settings;
  settings.set("integrator", integrator);
  settings.set("spp", spp);
  const RenderContext ctx = prepared->context(settings);
  auto integ = makeIntegrator(ctx);
  Film film(w, h);
  {
    Phase p{"render"};
    renderImage(*integ, film);
  }
  return 0;
}

// texture_bench: what textures cost. (1) ns per TextureSampler lookup on one thread: bilinear
// magnification and trilinear minification of a 1024x1024 image; (2) a Whitted render of
// scenes/textured.gltf with its textures and with them stripped (factors only), and the
// overhead. Usage: texture_bench [scene.gltf] [WxH] [threads]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>

#include "accel/registry.h"
#include "core/render_setup.h"
#include "core/renderer.h"
#include "core/texture_sampler.h"
#include "integrators/registry.h"
#include "io/gltf_loader.h"

using namespace tray;

namespace {

double secondsOf(const std::function<void()>& f) {
  auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void lookups() {
  std::vector<TextureImage> images(1);
  TextureImage& im = images[0];
  im.name = "noise";
  im.width = im.height = 1024;
  im.pixels.resize(size_t(1024) * 1024 * 3);
  uint32_t state = 1;
  for (float& v : im.pixels) v = float((state = state * 1664525u + 1013904223u) >> 8) / 16777216.0f;
  TextureSampler sampler(images);
  TextureRef ref;
  ref.image = 0;
  const int n = 1 << 20;
  for (float texels : {0.0f, 4.0f}) {
    float d = texels / 1024, sum = 0;
    sampler.sample(ref, {{0.5f, 0.5f}, {d, 0}, {0, d}});  // first touch builds the MIP levels
    double s = secondsOf([&] {
      for (int i = 0; i < n; ++i) {
        float u = float(i % 977) / 977, v = float(i % 1013) / 1013;
        sum += sampler.sample(ref, {{u, v}, {d, 0}, {0, d}}).x;
      }
    });
    std::printf("lookup %-34s %6.0f ns  (checksum %.3f)\n",
                texels == 0 ? "bilinear (magnified, no MIP):" : "trilinear (4-texel footprint):",
                s / n * 1e9, sum / n);
  }
}

RenderStats render(const Scene& scene, const Camera& camera, ImageSize size, int threads) {
  auto accel = makeAccelerator("embree", scene);
  RenderSettings s;
  s.set("integrator", "whitted");
  RenderContext ctx{scene, *accel, camera, s, size.width, size.height};
  auto integrator = makeIntegrator(ctx);
  Film film(size.width, size.height);
  RenderOptions opt;
  opt.threads = threads;
  return renderImage(*integrator, film, opt);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string path =
        argc > 1 ? argv[1] : std::string(TRAY_SOURCE_DIR) + "/scenes/textured.gltf";
    lookups();
    Scene textured = loadGltf(path);
    Scene plain = textured;
    plain.textures.clear();
    for (Material& m : plain.materials)
      m.baseColorTexture = m.metallicRoughnessTexture = m.emissiveTexture = m.normalTexture = {};
    CameraDesc cam = chooseCamera(textured, -1);
    ImageSize size = resolveImageSize(argc > 2 ? argv[2] : "", cam);
    const int threads = argc > 3 ? std::atoi(argv[3]) : 0;
    auto camera = Camera::create(cam, size.width, size.height);
    render(textured, *camera, size, threads);  // warm-up: MIP levels, caches
    RenderStats a = render(textured, *camera, size, threads);
    RenderStats b = render(plain, *camera, size, threads);
    std::printf(
        "%s %dx%d whitted: textured %.3f s (%.2f Mrays/s), untextured %.3f s (%.2f Mrays/s): "
        "textures add %.0f%%\n",
        path.c_str(), size.width, size.height, a.seconds, a.mraysPerSecond(), b.seconds,
        b.mraysPerSecond(), (a.seconds / b.seconds - 1) * 100);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "texture_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}

// texture_bench: what textures cost. (1) lookups per second on one thread, TRay's own filter
// against OIIO's TextureSystem in the same run (ratio), bilinear magnification and trilinear
// minification of a 2048x2048 8-bit sRGB image; (2) a Whitted render of
// scenes/textured.gltf with its textures and with them stripped (factors only), and the
// overhead; (3) on one thread, the time to make the MIP pyramid of that image: the stored coarse
// levels (TexturePyramid's constructor) and every 64 x 64 tile of levels 1-3.
// Usage: texture_bench [scene.gltf] [WxH] [threads]
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "accel/registry.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "textures/texture_pyramid.h"
#include "textures/texture_sampler.h"

using namespace tray;

namespace {

double secondsOf(const std::function<void()>& f) {
  auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// A 2048 x 2048 RGB image of 8-bit codes with the sRGB table, as the glTF loader keeps a
/// DamagedHelmet texture.
TextureImage codeImage(int size) {
  auto codes = std::make_shared<TexelCodes>();
  codes->bytes.resize(size_t(size) * size_t(size) * 3);
  uint32_t state = 1;
  for (auto& b : codes->bytes) b = (unsigned char)((state = state * 1664525u + 1013904223u) >> 24);
  auto table = std::make_shared<std::vector<float>>(256);
  for (int i = 0; i < 256; ++i) {
    const float c = float(i) / 255.0f;
    (*table)[size_t(i)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
  }
  TextureImage im;
  im.name = "noise";
  im.width = im.height = size;
  im.codes = codes;
  im.table = table;
  return im;
}

/// Lookups per second on one thread, TRay's filter and OIIO's TextureSystem on the same image
/// in the same run: magnified (bilinear in level 0) and minified (trilinear, 4 and 40 texels:
/// levels 1-3 in tiles, then stored levels), uvs spread over the image as a path tracer's are.
void lookups() {
  const int size = 2048;
  std::vector<TextureImage> images{codeImage(size)};
  const TextureSampler tray(images, 0, TextureBackend::kTray),
      oiio(images, 0, TextureBackend::kOiio);
  TextureRef ref;
  ref.image = 0;
  const int n = 1 << 21;
  for (float texels : {0.0f, 4.0f, 40.0f}) {
    const float d = texels / float(size);
    auto run = [&](const TextureSampler& sampler, float& checksum) {
      for (int i = 0; i < n; i += 97)  // first touch: OIIO's tiles, TRay's MIP tiles
        sampler.sample(ref, {{float(i % 977) / 977, float(i % 1013) / 1013}, {d, 0}, {0, d}});
      return secondsOf([&] {
        for (int i = 0; i < n; ++i) {
          const float u = float(i % 977) / 977, v = float((i * 7) % 1013) / 1013;
          checksum += sampler.sample(ref, {{u, v}, {d, 0}, {0, d}}).x;
        }
      });
    };
    float sumTray = 0, sumOiio = 0;
    const double oiioSeconds = run(oiio, sumOiio), traySeconds = run(tray, sumTray);
    std::printf(
        "lookup %-30s TRay %6.1f M/s (%5.0f ns), OIIO %6.1f M/s (%5.0f ns): %.2fx  (checksums "
        "%s)\n",
        texels == 0 ? "bilinear (magnified, level 0):"
                    : texels == 4 ? "trilinear (4-texel footprint):"
                                  : "trilinear (40-texel footprint):",
        n / traySeconds * 1e-6, traySeconds / n * 1e9, n / oiioSeconds * 1e-6,
        oiioSeconds / n * 1e9, oiioSeconds / traySeconds, sumTray == sumOiio ? "equal" : "DIFFER");
  }
}

/// One thread: TexturePyramid's constructor (stored levels) and then one texel() per tile of
/// levels 1..kComputed, finest first (so each tile reads made tiles), on a 2048^2 image; the
/// fastest of five, and a checksum of every tile's texels.
void pyramidMaking() {
  tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  const std::vector<TextureImage> images{codeImage(2048)};
  std::vector<double> construct, tiles;
  double checksum = 0;
  for (int run = 0; run < 5; ++run) {
    std::unique_ptr<TexturePyramid> p;
    construct.push_back(secondsOf([&] { p = std::make_unique<TexturePyramid>(images[0]); }));
    double sum = 0;
    tiles.push_back(secondsOf([&] {
      for (int level = 1; level <= TexturePyramid::kComputed; ++level)
        for (int y = 0; y < p->height(level); y += TexturePyramid::kTile)
          for (int x = 0; x < p->width(level); x += TexturePyramid::kTile) {
            float scratch[3];
            sum += double(p->texel(level, x, y, scratch)[0]);
          }
    }));
    for (int level = 1; level < p->levels(); ++level)  // every texel, outside the timing
      for (int y = 0; y < p->height(level); ++y)
        for (int x = 0; x < p->width(level); ++x) {
          float scratch[3];
          const float* t = p->texel(level, x, y, scratch);
          sum += double(t[0]) + double(t[1]) * 3 + double(t[2]) * 7;
        }
    checksum = sum;
  }
  const double c = *std::min_element(construct.begin(), construct.end());
  const double t = *std::min_element(tiles.begin(), tiles.end());
  std::printf(
      "pyramid of a 2048^2 8-bit RGB image, 1 thread, fastest of 5: stored levels %.2f ms, "
      "all tiles of levels 1-%d %.2f ms (%.1f Mtexels/s)  (checksum %.9g)\n",
      c * 1e3, TexturePyramid::kComputed, t * 1e3,
      double(TexturePyramid::tileBytesAtMost(2048, 2048)) / 12 / t * 1e-6, checksum);
}

RenderStats render(const Scene& scene, const CameraDesc& camera, ImageSize size, int threads) {
  RenderSettings s;
  s.set("integrator", "whitted");
  RenderOptions opt;
  opt.threads = threads;
  RenderStats stats;
  PreparedScene(scene, camera, size).render(s, opt, &stats);
  return stats;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string path =
        argc > 1 ? argv[1] : std::string(TRAY_SOURCE_DIR) + "/scenes/textured.gltf";
    lookups();
    pyramidMaking();
    Scene textured = loadGltf(path);
    Scene plain = textured;
    plain.textures.clear();
    for (Material& m : plain.materials)
      m.baseColorTexture = m.metallicRoughnessTexture = m.emissiveTexture = m.normalTexture = {};
    CameraDesc cam = chooseCamera(textured, -1);
    ImageSize size = resolveImageSize(argc > 2 ? argv[2] : "", cam);
    const int threads = argc > 3 ? std::atoi(argv[3]) : 0;
    render(textured, cam, size, threads);  // warm-up: MIP levels, caches
    RenderStats a = render(textured, cam, size, threads);
    RenderStats b = render(plain, cam, size, threads);
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

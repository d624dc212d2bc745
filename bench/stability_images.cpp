// Renders the images of docs/stability.md from the scenes the stability tests measure
// (tests/stability/stability_scenes.h), each with the fix and, where a counter-example exists,
// without it: `build/stability_images docs/stability`.
#include <cstdio>
#include <filesystem>

#include "io/image_output.h"
#include "tests/stability/stability_scenes.h"

using namespace tray;
using namespace tray::stability;

namespace {

constexpr int kW = 160, kH = 120;
std::string outDir;

void save(const Film& f, const std::string& name) {
  const std::string path = outDir + "/" + name + ".png";
  writeImage(f, path);
  std::printf("wrote %s\n", path.c_str());
}

/// Direct light only (max depth 2).
RenderSettings directPath(int spp) {
  RenderSettings s = pathSettings(spp);
  s.set("max-depth", 2);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: stability_images OUT_DIR\n");
    return 2;
  }
  outDir = argv[1];
  std::filesystem::create_directories(outDir);

  // 1. Self-intersection: the scene scaled by 1e4, direct light (path, max depth 2) against a
  // fixed shadow-ray epsilon of 1e-4.
  {
    SceneWithCamera big = acneScene(1e4f, Vec3(0.0f), false);
    save(renderFilm(big.scene, big.camera, kW, kH, directPath(4)), "1-scale-1e4-robust-offset");
    save(renderFixedEpsilon(big, kW, kH, 1e-4f), "1-scale-1e4-fixed-epsilon");
    SceneWithCamera far = acneScene(1.0f, Vec3(1e5f, 0, 1e5f), false);
    save(renderFixedEpsilon(far, kW, kH, 0.0f), "1-moved-1e5-no-offset");
  }
  // 2. Watertightness: a tessellated sphere lit from behind the camera, bvh accelerator.
  {
    Scene s;
    addMeshInstance(s, addMesh(s, geodesicSphere(3, addMaterial(s, diffuse(Color(0.8f))))),
                    Mat4::identity());
    s.environment.background = Color(0.0f, 0.0f, 1.0f);
    s.lights.push_back(pointLight({0, 0, 5}, Color(25.0f)));
    s.finalize();
    save(renderFilm(s, lookAt({0, 0, 3}, {0, 0, 0}, 0.8f), kW, kH, RenderSettings{}, nullptr, {},
                    "bvh"),
         "2-geodesic-sphere-bvh");
  }
  // 3. Light trapped by total internal reflection.
  {
    SceneWithCamera a = trappedLightScene();
    RenderSettings w;
    w.set("max-depth", 64);
    save(renderFilm(a.scene, a.camera, kW, kH, w), "3-tir-whitted");
    save(renderFilm(a.scene, a.camera, kW, kH, pathSettings(64)), "3-tir-path");
  }
  // 4. Caustics: 64 spp unclamped, clamped, and the unclamped 1024 spp reference.
  {
    SceneWithCamera c = causticScene();
    save(renderFilm(c.scene, c.camera, kW, kH, pathSettings(64)), "4-caustic-64spp");
    save(renderFilm(c.scene, c.camera, kW, kH, pathSettings(64, 10.0f)),
         "4-caustic-64spp-clamp-10");
    save(renderFilm(c.scene, c.camera, kW, kH, pathSettings(64, 0, "sobol")),
         "4-caustic-64spp-sobol");
    save(renderFilm(c.scene, c.camera, kW, kH, pathSettings(1024)), "4-caustic-1024spp-reference");
  }
  // 7. NaN normals on every 5th vertex: flat facets, no NaN pixels.
  {
    TriangleMesh m = smoothSphere();
    poisonNormals(m);
    SceneWithCamera a = meshOnFloor(std::move(m));
    save(renderFilm(a.scene, a.camera, kW, kH, pathSettings(16)), "7-nan-normals-path");
  }
  return 0;
}

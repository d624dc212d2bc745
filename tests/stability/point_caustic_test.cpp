// Stability 8: a caustic path tracing cannot find. scenes/transport/caustic-spot.gltf: a spot
// light aimed at a smooth glass ball above a diffuse floor, its cone inside the ball's
// silhouette, so that every bit of light on the floor came off or through the ball (paths
// L S S D E). A point light is never hit by a BSDF-sampled ray and next-event estimation from
// the floor cannot pass the ball's refraction: `path` renders the floor black at any sample
// count. Photon mapping and bidirectional path tracing find the caustic; their power on the
// visible floor is checked against the ray-optics quadrature of tools/caustic_power.py.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "gltf/gltf_loader.h"
#include "tests/render_film.h"

namespace tray {
namespace {

// tools/caustic_power.py (quadrature of 6M light rays, exact Fresnel, <= 1 internal
// reflection: the paths of --max-depth 5): the caustic's power on the measured floor, watts.
constexpr double kReferencePower = 0.534954;
// The scene's constants (tools/make-transport-scenes.py).
constexpr int kImageSize = 200;
constexpr double kViewHalf = 2.5, kViewCenterX = 2.0, kExcludedRadius = 0.6, kAlbedo = 0.5;

/// The power (W) arriving on the floor pixels the ball does not hide: radiance rho E / pi per
/// pixel, times pi / rho and the pixel's area.
double floorPower(const Film& f) {
  const double pixel = 2 * kViewHalf / kImageSize;
  double sum = 0;
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x) {
      const double wx = kViewCenterX - kViewHalf + (x + 0.5) * pixel;
      const double wz = -kViewHalf + (y + 0.5) * pixel;
      if (std::hypot(wx, wz) <= kExcludedRadius) continue;
      sum += f.pixel(Film::kBeauty, x, y)[0];
    }
  return sum * kPi / kAlbedo * pixel * pixel;
}

Film render(const std::string& integrator, int spp, RenderSettings s = {}) {
  const Scene scene =
      loadGltf(std::string(TRAY_SOURCE_DIR) + "/scenes/transport/caustic-spot.gltf");
  s.set("integrator", integrator);
  s.set("spp", spp);
  s.set("max-depth", 5);
  return test::renderFilm(scene, scene.cameras.at(0), kImageSize, kImageSize, s);
}

TEST(PointCaustic, PathTracingRendersTheFloorBlack) {
  const double power = floorPower(render("path", 64));
  std::printf("path, 64 spp: %.6f W of %.6f W\n", power, kReferencePower);
  EXPECT_LT(power, 1e-3 * kReferencePower);
}

TEST(PointCaustic, BdptFindsTheCaustic) {
  // Light tracing (t = 1) connects the light subpaths that left the ball (L S S D) to the
  // camera; MIS with the other strategies keeps it unbiased. 4 spp: 160,000 light paths.
  const double power = floorPower(render("bdpt", 4));
  std::printf("bdpt, 4 spp: %.6f W of %.6f W (%+.2f%%)\n", power, kReferencePower,
              100 * (power / kReferencePower - 1));
  EXPECT_NEAR(power / kReferencePower, 1.0, 0.01);
}

TEST(PointCaustic, PhotonMappingFindsTheCaustic) {
  // Photons leave the spot, cross the ball and land on the floor, where each pixel's visible
  // point gathers them. 16 iterations of 50,000 photons; consistent, so a small bias (the
  // radius blurs the caustic's edge, which moves no power across the measured floor) remains.
  RenderSettings s;
  s.set("photons", 50000);
  const double power = floorPower(render("sppm", 16, s));
  std::printf("sppm, 16 x 50k photons: %.6f W of %.6f W (%+.2f%%)\n", power, kReferencePower,
              100 * (power / kReferencePower - 1));
  EXPECT_NEAR(power / kReferencePower, 1.0, 0.01);
}

}  // namespace
}  // namespace tray

// Depth of field: a thin lens images its plane in focus sharply and spreads any other depth
// into the aperture's shape, a disk of the thin-lens circle of confusion's radius.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/camera.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr int kSize = 64;
constexpr float kYfov = 0.8f, kFocus = 4.0f;

CameraDesc lensCamera(float radius, int blades = 0) {
  CameraDesc c = lookAt(Vec3(0, 0, 0), Vec3(0, 0, -1), kYfov);
  c.lensRadius = radius;
  c.focusDistance = kFocus;
  c.apertureBlades = blades;
  return c;
}

TEST(ThinLens, ThePlaneInFocusIsSharp) {
  // Every lens ray of a pixel position meets the pinhole ray of the same position in the plane
  // z = -focus: what lies there has the pinhole's image.
  const auto lens = Camera::create(lensCamera(0.3f), kSize, kSize);
  const auto pinhole = Camera::create(lensCamera(0.0f), kSize, kSize);
  EXPECT_TRUE(lens->hasLens());
  EXPECT_FALSE(pinhole->hasLens());
  for (float x : {0.5f, 17.25f, 63.5f})
    for (float y : {0.5f, 40.75f})
      for (float u : {0.0f, 0.3f, 0.99f}) {
        const Ray p = pinhole->generateRay(x, y), r = lens->generateLensRay(x, y, {u, 1 - u});
        const Vec3 atP = p.o + (-kFocus / p.d.z) * p.d, atR = r.o + (-kFocus / r.d.z) * r.d;
        EXPECT_LT(length(atP - atR), 1e-5f) << x << "," << y << " u " << u;
        EXPECT_NEAR(length(r.d), 1.0f, 1e-6f);
      }
}

TEST(ThinLens, PolygonApertureIsUniformInsideTheNGon) {
  for (int blades : {3, 6}) {
    int wedge[6] = {0, 0, 0, 0, 0, 0};
    double cx = 0, cy = 0;
    const int g = 60, n = g * g;  // 60 columns split evenly among 3 or 6 wedges
    const float apothem = std::cos(kPi / float(blades));
    for (int i = 0; i < n; ++i) {
      const Vec2 p = sampleAperture({(i % g + 0.5f) / g, (i / g + 0.5f) / g}, blades);
      cx += p.x, cy += p.y;
      // Inside every edge: the projection on each edge's outward normal is below the apothem.
      float angle = std::atan2(p.y, p.x) - 0.5f * kPi;
      angle -= 2 * kPi * std::floor(angle / (2 * kPi));
      const int k = std::min(int(angle / (2 * kPi / blades)), blades - 1);
      ++wedge[k];
      const float mid = 0.5f * kPi + (k + 0.5f) * 2 * kPi / blades;
      EXPECT_LE(p.x * std::cos(mid) + p.y * std::sin(mid), apothem + 1e-5f);
    }
    for (int k = 0; k < blades; ++k) EXPECT_NEAR(wedge[k], n / blades, n / blades / 50 + 2);
    EXPECT_NEAR(cx / n, 0.0, 2e-3);
    EXPECT_NEAR(cy / n, 0.0, 2e-3);
  }
}

/// An emissive sphere of radius 0.1 at view depth `depth` on the axis, nothing else.
Scene emitterAt(float depth) {
  Scene s;
  Material m = diffuse(Color(0.0f));
  m.emissive = Color(1.0f);
  addSphere(s, Vec3(0, 0, -depth), 0.1f, addMaterial(s, m));
  s.finalize();
  return s;
}

/// The image's radiance-weighted mean squared distance from its centroid, in pixels^2.
double secondMoment(const Film& f) {
  double sum = 0, sx = 0, sy = 0, sr = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double v = f.pixel(Film::kBeauty, x, y)[0];
      sum += v, sx += v * (x + 0.5), sy += v * (y + 0.5);
    }
  const double mx = sx / sum, my = sy / sum;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double dx = x + 0.5 - mx, dy = y + 0.5 - my;
      sr += f.pixel(Film::kBeauty, x, y)[0] * (dx * dx + dy * dy);
    }
  return sr / sum;
}

Film render(const Scene& s, const CameraDesc& cam, const std::string& accel = "embree") {
  RenderSettings st;
  st.set("spp", 64);
  st.set("pixel-sampler", "jitter");
  return renderFilm(s, cam, kSize, kSize, st, nullptr, {}, accel);
}

TEST(ThinLens, OutOfFocusPointsBlurIntoTheCircleOfConfusion) {
  // Thin lens: a point at depth z spreads over the plane in focus into a disk of radius
  // R |f - z| / z, i.e. R |f - z| / z / (2 tan(fov/2) f / H) pixels. Second moments add under
  // convolution, and a uniform disk of radius c has E[r^2] = c^2 / 2: the blurred image's
  // E[r^2] minus the pinhole image's is c^2 / 2.
  const float R = 0.3f, z = 2.0f;
  const Scene s = emitterAt(z);
  const double pinhole = secondMoment(render(s, lensCamera(0.0f)));
  const double blurred = secondMoment(render(s, lensCamera(R)));
  const double pixel = 2 * std::tan(kYfov / 2) * kFocus / kSize;  // at the plane in focus
  const double expected = R * std::fabs(kFocus - z) / z / pixel;
  const double measured = std::sqrt(2 * (blurred - pinhole));
  EXPECT_NEAR(measured, expected, 0.25) << "circle of confusion " << expected << " px";
  std::printf("circle of confusion: %.3f px measured, %.3f px by the formula\n", measured,
              expected);
  EXPECT_GT(expected, 5.0);

  // In the plane in focus the same lens leaves the image as the pinhole's (the sphere's own
  // depth, +-0.1, blurs by under 0.15 px).
  const Scene inFocus = emitterAt(kFocus);
  EXPECT_NEAR(secondMoment(render(inFocus, lensCamera(R))),
              secondMoment(render(inFocus, lensCamera(0.0f))), 0.1);
}

TEST(ThinLens, EmbreeAndBvhGiveTheSameImage) {
  const Scene s = emitterAt(2.0f);
  const Film a = render(s, lensCamera(0.3f, 6), "embree");
  const Film b = render(s, lensCamera(0.3f, 6), "bvh");
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int k = 0; k < 4; ++k)
        ASSERT_NEAR(a.pixel(Film::kBeauty, x, y)[k], b.pixel(Film::kBeauty, x, y)[k], 1e-6f)
            << x << "," << y;
}

TEST(ThinLens, NeedsAFocusDistance) {
  CameraDesc c = lensCamera(0.3f);
  c.focusDistance = 0;
  EXPECT_THROW(Camera::create(c, 8, 8), Error);
}

}  // namespace
}  // namespace tray

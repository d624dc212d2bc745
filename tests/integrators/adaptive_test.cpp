#include "integrators/adaptive.h"

#include <gtest/gtest.h>

#include <cstdio>

#include <cmath>

#include "accel/registry.h"
#include "core/error.h"
#include "film/aov.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "tests/raster_function.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

struct Result {
  Film film;
  RenderStats stats;
  size_t traced = 0;
};

/// Renders with `integrator`, filling the samples AOV.
Result render(const Integrator& integrator, int w, int h, int threads = 0) {
  Film film(w, h);
  RenderOptions opt;
  opt.threads = threads;
  opt.aovs = {"samples"};
  RenderStats st = renderImage(integrator, film, opt);
  return {std::move(film), st, adaptiveTracedPoints(integrator)};
}

float samplesAt(const Film& f, int x, int y) {
  return f.pixel(f.findLayer("samples"), x, y)[0];
}
float valueAt(const Film& f, int x, int y) {
  return f.pixel(Film::kBeauty, x, y)[0];
}

RenderSettings adaptiveSettings(int depth = 4, float threshold = 0.05f) {
  RenderSettings s;
  s.set("integrator", "adaptive");
  s.set("aa-depth", depth);
  s.set("aa-threshold", threshold);
  return s;
}

TEST(Adaptive, ContrastIsBoundedAndPerceptual) {
  const Color same[2] = {Color(0.3f), Color(0.3f)};
  EXPECT_EQ(adaptiveContrast(same, 2), 0.0f);
  const Color extreme[2] = {Color(0.0f), Color(1e6f)};
  EXPECT_LE(adaptiveContrast(extreme, 2), 1.0f);
  EXPECT_GT(adaptiveContrast(extreme, 2), 0.99f);
  // The same absolute step matters more in the dark than in the bright.
  const Color dark[2] = {Color(0.01f), Color(0.06f)}, bright[2] = {Color(5.0f), Color(5.05f)};
  EXPECT_GT(adaptiveContrast(dark, 2), 10 * adaptiveContrast(bright, 2));
  // Chromatic edges of equal luminance still count.
  const Color hue[2] = {Color(0.5f, 0.1f, 0.1f), Color(0.1f, 0.1f, 0.5f)};
  EXPECT_GT(adaptiveContrast(hue, 2), 0.2f);
}

TEST(Adaptive, FlatRegionUsesOnlyPixelCorners) {
  RasterWorld world;
  const int W = 20, H = 12;
  RenderContext ctx = world.context(adaptiveSettings(), W, H);
  auto inner =
      std::make_unique<RasterIntegrator>(ctx, RasterImage{[](float, float) { return 0.5f; }});
  const RasterIntegrator& counter = *inner;
  auto adaptive = makeAdaptiveAround(ctx, std::move(inner));
  Result r = render(*adaptive, W, H);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      EXPECT_EQ(samplesAt(r.film, x, y), 4.0f);
      EXPECT_FLOAT_EQ(valueAt(r.film, x, y), 0.5f);
    }
  // Corners are shared: (W + 1)(H + 1) rays in all, about one per pixel.
  EXPECT_EQ(counter.calls.load(), uint64_t((W + 1) * (H + 1)));
  EXPECT_EQ(r.stats.rays.cameraRays, uint64_t((W + 1) * (H + 1)));
}

/// A disc and a step edge: curved and straight boundaries at every subpixel offset.
RasterImage discAndEdge() {
  return {[](float x, float y) {
            float dx = x - 9.3f, dy = y - 7.1f;
            return (dx * dx + dy * dy < 20.0f ? 1.0f : 0.0f) + (x > 17.37f ? 0.5f : 0.0f);
          },
          [](float x, float y) {
            float dx = x - 9.3f, dy = y - 7.1f;
            return dx * dx + dy * dy < 20.0f ? 1 : -1;
          }};
}

TEST(Adaptive, EveryLatticePointIsTracedExactlyOnceAcrossThreads) {
  RasterWorld world;
  const int W = 24, H = 16;
  RenderContext ctx = world.context(adaptiveSettings(), W, H);
  auto inner = std::make_unique<RasterIntegrator>(ctx, discAndEdge(), true);
  const RasterIntegrator& counter = *inner;
  auto adaptive = makeAdaptiveAround(ctx, std::move(inner));
  Result r = render(*adaptive, W, H, 2);
  EXPECT_EQ(counter.calls.load(), r.traced);
  EXPECT_EQ(r.stats.rays.cameraRays, r.traced);
  std::set<std::pair<float, float>> distinct;
  for (Vec2 p : counter.positions) distinct.insert({p.x, p.y});
  EXPECT_EQ(distinct.size(), counter.positions.size());  // no point traced twice
  EXPECT_GT(r.traced, size_t((W + 1) * (H + 1)));        // and the edges did subdivide
}

TEST(Adaptive, EdgesSubdivideToTheMaximumDepth) {
  RasterWorld world;
  const int W = 24, H = 16;
  for (int depth : {2, 4}) {
    RenderContext ctx = world.context(adaptiveSettings(depth), W, H);
    auto adaptive =
        makeAdaptiveAround(ctx, std::make_unique<RasterIntegrator>(ctx, discAndEdge(), true));
    Result r = render(*adaptive, W, H);
    // Pixel 17 straddles the step at x = 17.37: the squares along it halve `depth` times, so
    // the pixel uses two full columns of finest-level points and its coverage is exact to
    // one finest column (1 / 2^depth of a pixel).
    const int n = 1 << depth;
    for (int y = 0; y < H; ++y) {
      EXPECT_GE(samplesAt(r.film, 17, y), 2.0f * (n + 1)) << y;
      EXPECT_NEAR(valueAt(r.film, 17, y), 0.5f * 0.63f, 0.5f / n + 1e-6f) << y;
      EXPECT_EQ(samplesAt(r.film, 22, y), 4.0f) << y;  // flat: corners only
    }
  }
}

/// A lit sphere on a floor, for thread-count determinism with a real inner integrator.
Scene sphereScene() {
  Scene s;
  int mat = addMaterial(s, diffuse(Color(0.7f, 0.5f, 0.3f)));
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), mat);
  addSphere(s, {0, 1, 0}, 1.0f, addMaterial(s, diffuse(Color(0.2f, 0.6f, 0.9f))));
  s.lights.push_back(pointLight({2, 5, 2}, Color(40.0f)));
  s.environment.background = Color(0.2f, 0.3f, 0.5f);
  s.finalize();
  return s;
}

TEST(Adaptive, SameImageAndRayCountsForOneAndTwoThreads) {
  Scene scene = sphereScene();
  const int W = 48, H = 32;
  for (bool robust : {false, true}) {
    RenderSettings s = adaptiveSettings();
    s.set("inner", "whitted");
    s.set("aa-robust", robust);
    const PreparedScene prepared(scene, lookAt({0, 3, 6}, {0, 0.5f, 0}), {W, H});
    const RenderContext ctx = prepared.context(s);
    auto one = makeIntegrator(ctx), two = makeIntegrator(ctx);
    Result a = render(*one, W, H, 1), b = render(*two, W, H, 2);
    EXPECT_EQ(a.film.layers()[0].data, b.film.layers()[0].data) << robust;
    const int layer = a.film.findLayer("samples");
    EXPECT_EQ(a.film.layers()[size_t(layer)].data, b.film.layers()[size_t(layer)].data) << robust;
    EXPECT_EQ(a.stats.rays.cameraRays, b.stats.rays.cameraRays) << robust;
    EXPECT_EQ(a.traced, b.traced) << robust;
  }
}

// Issue 40: the lattice cache held every point of the image (2.79 GB for a textured asset at
// 960 x 720). Bands of rows no pixel will read again are dropped (integrators/lattice_cache.h):
// on a tall image the most points kept at once is a small part of those traced, each point is
// still traced once (rays = points), and the image is the same for 1 and 4 threads.
TEST(Adaptive, KeepsOnlyTheBandsPixelsStillRead) {
  // A column of small spheres, so that every band of rows has edges to subdivide.
  Scene scene;
  const int mat = addMaterial(scene, diffuse(Color(0.2f, 0.6f, 0.9f)));
  for (int k = 0; k < 16; ++k) addSphere(scene, {0.1f * float(k % 3), float(k) - 7.5f, 0}, 0.3f, mat);
  scene.lights.push_back(pointLight({2, 0, 6}, Color(400.0f)));
  scene.environment.background = Color(0.2f, 0.3f, 0.5f);
  scene.finalize();
  const int W = 24, H = 256;  // 16 bands of 16 rows
  for (bool robust : {false, true}) {
    RenderSettings s = adaptiveSettings(3);
    s.set("inner", "whitted");
    s.set("aa-robust", robust);
    const PreparedScene prepared(scene, lookAt({0, 0, 20}, {0, 0, 0}, 0.85f), {W, H});
    const RenderContext ctx = prepared.context(s);
    auto one = makeIntegrator(ctx), four = makeIntegrator(ctx);
    Result a = render(*one, W, H, 1), b = render(*four, W, H, 4);
    EXPECT_EQ(a.film.layers()[0].data, b.film.layers()[0].data) << robust;
    EXPECT_EQ(a.stats.rays.cameraRays, a.traced) << robust;  // none traced twice
    EXPECT_EQ(a.traced, b.traced) << robust;
    EXPECT_GT(a.traced, size_t((W + 1) * (H + 1))) << robust;  // it did subdivide
    EXPECT_LT(adaptivePeakKeptPoints(*one), a.traced / 3) << robust;
    EXPECT_LT(adaptivePeakKeptPoints(*four), b.traced / 2) << robust;
    std::printf("robust %d: %zu points traced, at most %zu kept (1 thread), %zu (4 threads)\n",
                int(robust), a.traced, adaptivePeakKeptPoints(*one),
                adaptivePeakKeptPoints(*four));
  }
}

// --- Where corner sampling fails: features thinner than a pixel -----------------------------

/// Emissive poles 0.2 px wide between the pixel corners (upper rows) and emissive spheres
/// 0.7 px across centred between corners (lower rows), on black, seen by an orthographic camera
/// at 0.2 world units per pixel.
constexpr int kThinW = 64, kThinH = 48, kPoleRows = 30;
constexpr float kUnit = 0.2f;  // world units per pixel

Scene thinScene() {
  Scene s;
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(1.0f);
  const int mat = addMaterial(s, glow);
  auto world = [](float px, float py) { return Vec3(px * kUnit - 6.4f, 4.8f - py * kUnit, 0); };
  for (int k = 0; k < 7; ++k) {  // poles centred at x = 8k + 4.35 px, 0.2 px wide
    const Vec3 c = world(8.0f * k + 4.35f, kPoleRows * 0.5f);
    addShape(s,
             std::make_shared<Box>(Vec3(-0.1f * kUnit, -kPoleRows * 0.5f * kUnit, -0.1f),
                                   Vec3(0.1f * kUnit, kPoleRows * 0.5f * kUnit, 0.1f)),
             Mat4::translate(c), mat);
  }
  for (int k = 0; k < 12; ++k)  // spheres 0.7 px across, off the corner lattice
    addSphere(s, world(5.0f * k + 3.5f, 34.5f + float(k % 4) * 3), 0.35f * kUnit, mat);
  s.finalize();
  return s;
}

Film renderThin(const Scene& scene, const RenderSettings& settings) {
  CameraDesc cd = lookAt({0, 0, 10}, {0, 0, 0});
  cd.type = CameraDesc::Type::kOrthographic;
  cd.ymag = kThinH * 0.5f * kUnit;
  const PreparedScene prepared(scene, cd, {kThinW, kThinH});
  const RenderContext ctx = prepared.context(settings);
  auto integrator = makeIntegrator(ctx);
  return render(*integrator, kThinW, kThinH).film;
}

double rmse(const Film& a, const Film& b) {
  double sum = 0;
  for (int y = 0; y < kThinH; ++y)
    for (int x = 0; x < kThinW; ++x) sum += std::pow(valueAt(a, x, y) - valueAt(b, x, y), 2.0);
  return std::sqrt(sum / (kThinW * kThinH));
}

/// Share of (pole, row) pairs whose light (summed over the pole's pixel and its neighbours) is
/// under half the reference's.
double missingPoleRows(const Film& f, const Film& reference) {
  int missing = 0, total = 0;
  for (int k = 0; k < 7; ++k)
    for (int y = 0; y < kPoleRows; ++y) {
      double got = 0, want = 0;
      for (int x = 8 * k + 3; x <= 8 * k + 5; ++x)
        got += valueAt(f, x, y), want += valueAt(reference, x, y);
      missing += got < 0.5 * want;
      ++total;
    }
  return double(missing) / total;
}

TEST(Adaptive, ThinFeaturesAreMissedByCornersAndFoundByTheRobustMode) {
  const Scene scene = thinScene();
  RenderSettings ref;
  ref.set("pixel-sampler", "grid"), ref.set("spp", 32 * 32);
  const Film reference = renderThin(scene, ref);
  RenderSettings plain = adaptiveSettings();
  plain.set("inner", "whitted");
  RenderSettings robust = plain;
  robust.set("aa-robust", true);
  const Film a = renderThin(scene, plain), b = renderThin(scene, robust);
  const double plainError = rmse(a, reference), robustError = rmse(b, reference);
  const double plainMissing = missingPoleRows(a, reference),
               robustMissing = missingPoleRows(b, reference);
  std::printf(
      "thin features vs 32x32 grid: plain adaptive RMSE %.4f, %.0f%% pole rows missing; "
      "robust RMSE %.4f, %.1f%% missing\n",
      plainError, 100 * plainMissing, robustError, 100 * robustMissing);
  EXPECT_GT(plainMissing, 0.95);  // corners on the integer lattice never touch the poles
  EXPECT_LT(robustMissing, 0.05);
  EXPECT_LT(robustError, 0.3 * plainError);
}

TEST(Adaptive, HeatmapRampsWithRaysPerPixel) {
  Film film(3, 1);
  int layer = film.addLayer("samples", {"count"});
  film.pixel(layer, 0, 0)[0] = 4, film.pixel(layer, 1, 0)[0] = 30, film.pixel(layer, 2, 0)[0] = 289;
  Film heat = samplesHeatmap(film);
  auto brightness = [&](int x) {
    return luminance(Color(heat.pixel(Film::kBeauty, x, 0)[0], heat.pixel(Film::kBeauty, x, 0)[1],
                           heat.pixel(Film::kBeauty, x, 0)[2]));
  };
  EXPECT_LT(brightness(0), brightness(1));
  EXPECT_LT(brightness(1), brightness(2));
  EXPECT_FLOAT_EQ(brightness(2), 1.0f);  // the maximum is white
  EXPECT_THROW(samplesHeatmap(Film(2, 2)), Error);
}

TEST(Adaptive, RejectsBadSettings) {
  RasterWorld world;
  RenderSettings s = adaptiveSettings(13);
  EXPECT_THROW(makeIntegrator(world.context(s, 4, 4)), Error);
  s = adaptiveSettings();
  s.set("inner", "adaptive");
  EXPECT_THROW(makeIntegrator(world.context(s, 4, 4)), Error);
}

}  // namespace
}  // namespace tray

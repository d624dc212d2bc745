// Motion blur (core/motion.h; docs/scene-format.md, "Motion blur"): the interpolation of motion
// steps as Embree does it, the box that holds every interpolated placement, a sphere sweeping
// across the frame giving the analytic coverage profile on both accelerators, and a static
// object rendering bit for bit as without motion blur.
#include "core/motion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

TEST(MotionSteps, InterpolateLinearlyWithinEachSegmentAsEmbree) {
  const std::vector<Mat4> steps = {Mat4::translate({0, 0, 0}), Mat4::translate({4, 0, 0}),
                                   Mat4::translate({4, 2, 0})};
  auto at = [&](float t) {
    const Mat4 m = interpolateSteps(steps, t);
    return Vec3(m.m[0][3], m.m[1][3], m.m[2][3]);
  };
  // Two segments: t in [0, 0.5] goes to the middle step, [0.5, 1] from it to the last.
  EXPECT_EQ(at(0.0f).x, 0.0f);
  EXPECT_FLOAT_EQ(at(0.25f).x, 2.0f);
  EXPECT_FLOAT_EQ(at(0.5f).x, 4.0f);
  EXPECT_FLOAT_EQ(at(0.5f).y, 0.0f);
  EXPECT_FLOAT_EQ(at(0.75f).y, 1.0f);
  EXPECT_EQ(at(1.0f).y, 2.0f);   // the last segment's end, exactly
  EXPECT_EQ(at(-1.0f).x, 0.0f);  // clamped to the shutter
  EXPECT_EQ(at(7.0f).y, 2.0f);
  // Entry by entry, not a rotation's slerp: halfway through a quarter turn the matrix is the
  // mean of the two: a 45-degree turn shrunk by cos 45 degrees.
  const std::vector<Mat4> turn = {Mat4(), Mat4::rotate(0, 0, 0.7071068f, 0.7071068f)};
  const Mat4 half = interpolateSteps(turn, 0.5f);
  EXPECT_NEAR(half.m[0][0], 0.5f, 1e-6f);
  EXPECT_NEAR(half.m[0][1], -0.5f, 1e-6f);
  EXPECT_NEAR(half.m[1][0], 0.5f, 1e-6f);
}

TEST(MotionSteps, FlatInstantsAreMissedAndStaticPrimitivesKeepTheirTransform) {
  Primitive p;
  p.toWorld = Transform(Mat4::translate({1, 2, 3}));
  Transform t;
  const Transform* placed = placementAt(p, 0.7f, t);
  ASSERT_EQ(placed, &p.toWorld);  // the primitive's own transform, not a copy
  EXPECT_EQ(placed->m.m[1][3], 2.0f);
  // A half turn about z between two steps passes through a matrix of zero scale in x and y.
  p.motion = {Mat4(), Mat4::rotate(0, 0, 1, 0)};
  EXPECT_EQ(placementAt(p, 0.5f, t), nullptr);
  EXPECT_EQ(placementAt(p, 0.25f, t), &t);
  EXPECT_TRUE(stepsMove(p.motion));
  EXPECT_FALSE(stepsMove({Mat4::translate({1, 0, 0}), Mat4::translate({1, 0, 0})}));
}

TEST(MotionSteps, BoundsHoldEveryInterpolatedPlacement) {
  Primitive p;
  p.motion = {Mat4::translate({-3, 0, 0}), Mat4::rotate(0, 0.3826834f, 0, 0.9238795f),
              Mat4::translate({0, 5, 1}) * Mat4::scale({2, 2, 2})};
  const Bounds3 local{Vec3(-1.0f), Vec3(1.0f)};
  const Bounds3 box = motionBounds(p, local);
  for (int k = 0; k <= 100; ++k) {
    Transform t;
    ASSERT_EQ(placementAt(p, k / 100.0f, t), &t);
    for (int c = 0; c < 8; ++c) {
      const Vec3 q = t.point({c & 1 ? 1.0f : -1.0f, c & 2 ? 1.0f : -1.0f, c & 4 ? 1.0f : -1.0f});
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(q[a], box.lo[a] - 1e-5f);
        EXPECT_LE(q[a], box.hi[a] + 1e-5f);
      }
    }
  }
}

// --- A sphere, a square and a deforming square sweeping across the frame ----------------------

constexpr int kW = 40, kH = 10;
constexpr float kUnit = 0.1f;                          // world units per pixel
constexpr float kRadius = 4 * kUnit;                   // 8 px across
constexpr float kFrom = -10 * kUnit, kTo = 6 * kUnit;  // centre's x at open and close (16 px)

/// What sweeps: a sphere (Embree user geometry, moved by its transform), a square mesh moved by
/// its instance's transform, a square mesh whose vertices move (TriangleMesh::positionSteps),
/// or the camera, the other way past a still sphere (CameraDesc::motion).
enum class Sweep { kSphere, kSquare, kDeformingSquare, kCamera };

/// The object's centre at step k of `steps` (the camera's offset is its negative).
Vec3 sweepCentre(int k, int steps) {
  return Vec3(kFrom + (kTo - kFrom) * float(k) / float(steps - 1), 0, 0);
}

/// An emissive object (radiance 1, no lights: pixel value = coverage) of half-width kRadius
/// whose centre moves along x from kFrom to kTo over the shutter through `steps` evenly spaced
/// steps, on black.
Scene sweepScene(Sweep kind, int steps) {
  Scene s;
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(1.0f);
  const int material = addMaterial(s, glow);
  auto centre = [&](int k) { return sweepCentre(k, steps); };
  TriangleMesh square;
  const float a = kRadius;
  square.positions = {{-a, -a, 0}, {a, -a, 0}, {a, a, 0}, {-a, a, 0}};
  square.indices = {0, 1, 2, 0, 2, 3};
  square.material = material;
  if (kind == Sweep::kCamera) {
    addSphere(s, {0, 0, 0}, kRadius, material);
  } else if (kind == Sweep::kDeformingSquare) {
    for (int k = 0; k < steps; ++k) {
      square.positionSteps.push_back(square.positions);
      for (Vec3& p : square.positionSteps.back()) p += centre(k);
    }
    addMeshInstance(s, addMesh(s, square), Mat4());
  } else {
    const uint32_t i = kind == Sweep::kSphere ? addSphere(s, {0, 0, 0}, kRadius, material)
                                              : addMeshInstance(s, addMesh(s, square), Mat4());
    for (int k = 0; k < steps; ++k) s.primitives[i].motion.push_back(Mat4::translate(centre(k)));
  }
  s.finalize();
  return s;
}

/// Orthographic, kUnit per pixel, the image centred on the origin: pixel x spans world
/// [(x - kW/2) kUnit, (x + 1 - kW/2) kUnit], row y spans [(kH/2 - y - 1) kUnit, (kH/2 - y) kUnit].
/// Sweep::kCamera: the camera moves by minus the centre's path.
CameraDesc sweepCamera(Sweep kind, int steps) {
  CameraDesc cd = lookAt({0, 0, 5}, {0, 0, 0});
  cd.type = CameraDesc::Type::kOrthographic;
  cd.ymag = kH * 0.5f * kUnit;
  cd.xmag = kW * 0.5f * kUnit;
  if (kind == Sweep::kCamera)
    for (int k = 0; k < steps; ++k)
      cd.motion.push_back(Mat4::translate(-1.0f * sweepCentre(k, steps)) * cd.toWorld.m);
  return cd;
}

/// The fraction of the pixel's area and of the shutter over which the object covers a point:
/// at height y its chord is [c - w, c + w] (sphere: w = sqrt(r^2 - y^2); square: w = r for
/// |y| < r), so a point x is covered while the centre c is within w of it, i.e. for
/// |[x - w, x + w] ∩ [from, to]| / (to - from) of the shutter. Integrated over the pixel by the
/// midpoint rule in doubles.
double analyticCoverage(Sweep kind, int px, int py) {
  constexpr int n = 200;
  const double r = kRadius;
  double sum = 0;
  for (int j = 0; j < n; ++j) {
    const double y = (kH * 0.5 - py - (j + 0.5) / n) * kUnit;
    if (!(std::fabs(y) < r)) continue;
    const bool round = kind == Sweep::kSphere || kind == Sweep::kCamera;
    const double w = round ? std::sqrt(r * r - y * y) : r;
    for (int i = 0; i < n; ++i) {
      const double x = (px - kW * 0.5 + (i + 0.5) / n) * kUnit;
      const double overlap = std::min(x + w, double(kTo)) - std::max(x - w, double(kFrom));
      sum += std::max(overlap, 0.0) / (kTo - kFrom);
    }
  }
  return sum / (double(n) * n);
}

constexpr int kSpp = 2048;

struct SweepCase {
  const char* accel;
  Sweep kind;
};

class Swept : public testing::TestWithParam<SweepCase> {};

std::string sweepName(const testing::TestParamInfo<SweepCase>& info) {
  const char* kinds[] = {"sphere", "square", "deforming_square", "camera"};
  return std::string(info.param.accel) + "_" + kinds[int(info.param.kind)];
}

// 2048 independent samples per pixel: a coverage estimate c has a standard error of
// sqrt(c (1 - c) / 2048), at most 0.011; each pixel must be within 4.5 of those (and exactly 0
// where the sweep never reaches). Without the ray's time the sphere would sit at one end
// (coverage 0 or 1 across the sweep): off by up to 1.
TEST_P(Swept, CoverageProfileIsTheOverlapOverTheTravel) {
  const SweepCase c = GetParam();
  for (int steps : {2, 3}) {
    const Scene scene = sweepScene(c.kind, steps);
    RenderSettings settings;
    settings.set("integrator", "whitted");
    settings.set("sampler", "independent");
    settings.set("spp", kSpp);
    const Film film =
        renderFilm(scene, sweepCamera(c.kind, steps), kW, kH, settings, nullptr, {}, c.accel);
    double worst = 0, peak = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const double want = analyticCoverage(c.kind, x, y);
        const double got = film.pixel(Film::kBeauty, x, y)[0];
        worst = std::max(worst, std::fabs(got - want));
        peak = std::max(peak, want);
        const double bound = 4.5 * std::sqrt(std::max(want * (1 - want), 1e-6) / kSpp);
        EXPECT_NEAR(got, want, bound) << "pixel " << x << "," << y << " steps " << steps;
        EXPECT_EQ(film.pixel(Film::kBeauty, x, y)[3], float(got));  // alpha: the same coverage
      }
    std::printf("%s, sweep %d, %d steps: worst |coverage - analytic| %.4f (peak %.3f)\n", c.accel,
                int(c.kind), steps, worst, peak);
    EXPECT_GT(peak, 0.4);  // the sweep is in the picture
  }
}

INSTANTIATE_TEST_SUITE_P(
    AcceleratorsAndMotions, Swept,
    testing::Values(SweepCase{"embree", Sweep::kSphere}, SweepCase{"bvh", Sweep::kSphere},
                    SweepCase{"embree", Sweep::kSquare}, SweepCase{"bvh", Sweep::kSquare},
                    SweepCase{"embree", Sweep::kDeformingSquare},
                    SweepCase{"bvh", Sweep::kDeformingSquare}, SweepCase{"embree", Sweep::kCamera},
                    SweepCase{"bvh", Sweep::kCamera}),
    sweepName);

// --- Static objects keep every bit -----------------------------------------------------------

/// A lit sphere on a floor; with `mover`, a small sphere far off to the side moves over the
/// shutter (so camera rays draw times) where no path of this image reaches it.
Scene stillLife(bool mover) {
  Scene s;
  const int grey = addMaterial(s, diffuse(Color(0.6f)));
  addSphere(s, {0, 0.5f, 0}, 0.5f, grey);
  addMeshInstance(s, addMesh(s, quadMesh(3, grey)), Mat4());
  s.lights.push_back(pointLight({1, 3, 2}, Color(20.0f)));
  if (mover) {
    const uint32_t i = addSphere(s, {0, 0, 0}, 0.01f, grey);
    s.primitives[i].motion = {Mat4::translate({5000, 10, 0}), Mat4::translate({5001, 10, 0})};
    s.primitives[i].toWorld = Transform(s.primitives[i].motion[0]);
  }
  s.finalize();
  return s;
}

TEST(MotionBlur, StaticObjectsRenderBitForBitAsWithoutMotion) {
  const Scene still = stillLife(false), moving = stillLife(true);
  ASSERT_TRUE(moving.moving());
  ASSERT_FALSE(still.moving());
  for (const char* accel : {"embree", "bvh"}) {
    RenderSettings settings;
    settings.set("integrator", "path");
    settings.set("spp", 4);
    const CameraDesc cam = lookAt({0, 1.5f, 3}, {0, 0.4f, 0});
    const Film a = renderFilm(still, cam, 32, 24, settings, nullptr, {}, accel);
    const Film b = renderFilm(moving, cam, 32, 24, settings, nullptr, {}, accel);
    size_t differ = 0;
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 32; ++x)
        for (int c = 0; c < 4; ++c)
          differ += a.pixel(Film::kBeauty, x, y)[c] != b.pixel(Film::kBeauty, x, y)[c];
    EXPECT_EQ(differ, 0u) << accel;
  }
}

}  // namespace
}  // namespace tray

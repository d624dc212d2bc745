// Emissive analytic shapes as area lights in the path tracer (NEE by Shape::sample + MIS):
// a torus, a disk, a capped cylinder and a capped cone over a Lambert floor. The floor's
// radiance is checked against an estimate that uses no light sampling at all: the irradiance
// from the shape by cosine-distributed rays (stratified) that only call Shape::intersect.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/sampling.h"
#include "shapes/quadric.h"
#include "shapes/torus.h"
#include "tests/integrators/path_probe.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr float kAlbedo = 0.6f, kLe = 1.5f;

struct Emitter {
  const char* name;
  std::shared_ptr<const Shape> shape;
  Mat4 place;
};

std::vector<Emitter> emitters() {
  const float c = std::cos(0.4f), s = std::sin(0.4f);  // half-angle quaternions
  return {
      {"torus", std::make_shared<Torus>(0.6f, 0.15f),
       Mat4::translate({0, 1.2f, 0}) * Mat4::rotate(s, 0, 0, c)},
      {"disk (facing down)", std::make_shared<Disk>(0.5f, 0.1f),
       Mat4::translate({0.2f, 1.0f, 0}) * Mat4::rotate(1, 0, 0, 0)},
      {"capped cylinder", std::make_shared<Quadric>(Quadric::Kind::kCylinder, 0.3f, 0.8f, true),
       Mat4::translate({0, 0.8f, 0}) * Mat4::rotate(0, 0, s, c)},
      {"capped cone", std::make_shared<Quadric>(Quadric::Kind::kCone, 0.4f, 0.7f, true),
       Mat4::translate({0, 0.9f, 0}) * Mat4::scale(Vec3(1.2f))},
  };
}

/// Radiance of the floor at `at` from the emitter by the path tracer (max depth 2: direct).
void pathEstimate(const Scene& s, const Vec3& at, int samples, double& mean, double& err) {
  PathProbe probe(s, 2);
  const Vec3 eye = at + Vec3(0.3f, 0.4f, 0.1f);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < samples; ++i) {
    Sampler sampler(3, uint32_t(i), 1);
    const double L = probe.Li(Ray{eye, normalize(at - eye)}, sampler).x;
    sum += L, sum2 += L * L;
  }
  mean = sum / samples;
  err = std::sqrt(std::max(0.0, sum2 / samples - mean * mean) / samples);
}

/// The same by irradiance: albedo / pi * Le * pi * P(a cosine-distributed ray hits the shape).
double gatherEstimate(const Emitter& e, const Vec3& at, int n) {
  const Transform toWorld(e.place);
  long hits = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float jitter1 = float((i * 7919 + j * 104729) % 1000) / 1000.0f;
      const float jitter2 = float((i * 104729 + j * 7919) % 997) / 997.0f;
      const Vec3 d = sampleCosineHemisphere(
          Vec2{(float(i) + jitter1) / float(n), (float(j) + jitter2) / float(n)});
      const Vec3 w(d.x, d.z, d.y);  // about +y
      Ray local{toWorld.inversePoint(at), toWorld.inverseVector(w), 0.0f, kInfinity};
      Hit h;
      hits += e.shape->intersect(local, h);
    }
  return kAlbedo * kLe * double(hits) / (double(n) * n);
}

TEST(PathShapeLights, EmissiveTorusDiskCylinderConeLightTheFloorAsGathered) {
  for (const Emitter& e : emitters()) {
    Scene s;
    addShape(s, std::make_shared<Plane>(), Mat4::identity(),
             addMaterial(s, diffuse(Color(kAlbedo))));
    Material glow = diffuse(Color(0.0f));
    glow.emissive = Color(kLe);
    addShape(s, e.shape, e.place, addMaterial(s, glow));
    s.finalize();
    for (Vec3 at : {Vec3(0.1f, 0, 0.2f), Vec3(1.1f, 0, -0.6f)}) {
      double mean, err;
      pathEstimate(s, at, 1 << 18, mean, err);  // a power of two: whole Sobol' blocks
      const double expected = gatherEstimate(e, at, 1000);
      std::printf("%-20s at x %.1f: gathered %.5f, path (NEE + MIS) %.5f +- %.5f\n", e.name, at.x,
                  expected, mean, err);
      EXPECT_GT(expected, 0.01) << e.name;
      EXPECT_LT(err, 0.01 * expected) << e.name;
      EXPECT_NEAR(mean, expected, 4 * err + 2e-3 * expected) << e.name << " at x " << at.x;
    }
  }
}

}  // namespace
}  // namespace tray

// Area lights in the path tracer (NEE + MIS) against Lambert's polygon irradiance: a one-sided
// emitter whose vertex normals oppose its winding (glTF: the winding alone defines the front
// face), and an emissive analytic box against the same box as a closed 12-triangle mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tests/integrators/path_probe.h"
#include "tests/polygon_irradiance.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr float kAlbedo = 0.6f;

/// An estimate and its standard error, from the samples' variance (conservative for Sobol'
/// points, whose error is below the independent-sample rate).
struct Estimate {
  double mean = 0, stdError = 0;
};

/// Mean radiance (red) leaving the Lambert floor (y = 0) at `at` towards a viewer above it,
/// at max depth 2 (direct light only: emission seen by light samples and by BSDF samples).
Estimate floorRadiance(const Scene& s, const Vec3& at, int samples = 20000) {
  PathProbe probe(s, 2);
  const Vec3 eye = at + Vec3(0.3f, 0.4f, 0.1f);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < samples; ++i) {
    Sampler sampler(7, uint32_t(i), 1);
    const double L = probe.Li(Ray{eye, normalize(at - eye)}, sampler).x;
    sum += L;
    sum2 += L * L;
  }
  const double mean = sum / samples, var = std::max(0.0, sum2 / samples - mean * mean);
  return {mean, std::sqrt(var / samples)};
}

int addFloor(Scene& s) {
  return int(addShape(s, std::make_shared<Plane>(), Mat4::identity(),
                      addMaterial(s, diffuse(Color(kAlbedo)))));
}

int addGlow(Scene& s, float Le) {
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(Le);
  return addMaterial(s, glow);
}

// --- Facing: the winding, not the vertex normals --------------------------------------------

const std::vector<Vec3> kQuad = {{-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}};

/// A one-sided quad of radiance 2 at height 2 over the floor, wound counter-clockwise seen
/// from below (its front faces -y), with vertex normals along -y (consistent) or +y (opposed).
Scene quadOverFloor(bool normalsOpposeWinding) {
  Scene s;
  addFloor(s);
  TriangleMesh m;
  m.positions = kQuad;
  m.indices = {0, 1, 2, 0, 2, 3};  // cross(p1 - p0, p2 - p0) points to -y
  m.normals.assign(4, Vec3(0, normalsOpposeWinding ? 1.0f : -1.0f, 0));
  m.material = addGlow(s, 2.0f);
  addMeshInstance(s, addMesh(s, m), Mat4::identity());
  s.finalize();
  return s;
}

TEST(PathAreaLights, EmitterWithNormalsOpposingItsWindingShinesFromItsWindingFront) {
  // glTF 2.0 3.7.2.1: the front face is the counter-clockwise one; normals do not define
  // facing. Light sampling and BSDF sampling must agree on it, or MIS drops the share of one
  // of them: the sum then falls short of the closed form.
  for (Vec3 at : {Vec3(0.3f, 0, 0.2f), Vec3(1.5f, 0, -0.7f)}) {
    const double expected = kAlbedo / kPi * 2.0 * polygonIrradiance(at, {0, 1, 0}, kQuad);
    const double consistent = floorRadiance(quadOverFloor(false), at).mean;
    const double opposed = floorRadiance(quadOverFloor(true), at).mean;
    EXPECT_NEAR(consistent, expected, 0.01 * expected) << "at x " << at.x;
    EXPECT_NEAR(opposed, expected, 0.01 * expected) << "at x " << at.x;
    EXPECT_NEAR(opposed, consistent, 0.01 * expected) << "at x " << at.x;
  }
}

// --- An emissive box: analytic shape and mesh agree -----------------------------------------

constexpr float kBoxLo = 1.0f, kBoxHi = 1.6f, kBoxHalf = 0.4f;

/// The faces of the box [-h, h] x [lo, hi] x [-h, h], each counter-clockwise seen from outside.
std::vector<std::vector<Vec3>> boxFaces() {
  const float h = kBoxHalf, lo = kBoxLo, hi = kBoxHi;
  return {{{-h, lo, -h}, {h, lo, -h}, {h, lo, h}, {-h, lo, h}},   // bottom (-y)
          {{-h, hi, -h}, {-h, hi, h}, {h, hi, h}, {h, hi, -h}},   // top (+y)
          {{-h, lo, -h}, {-h, lo, h}, {-h, hi, h}, {-h, hi, -h}},  // -x
          {{h, lo, -h}, {h, hi, -h}, {h, hi, h}, {h, lo, h}},      // +x
          {{-h, lo, -h}, {-h, hi, -h}, {h, hi, -h}, {h, lo, -h}},  // -z
          {{-h, lo, h}, {h, lo, h}, {h, hi, h}, {-h, hi, h}}};     // +z
}

/// Irradiance at floor point x from the box of unit radiance: the faces that face x (all
/// above its horizon), each by Lambert's formula.
double boxIrradiance(const Vec3& x) {
  double E = 0;
  for (const auto& f : boxFaces()) {
    Vec3 n = cross(f[1] - f[0], f[2] - f[0]);
    if (dot(n, x - f[0]) > 0) E += polygonIrradiance(x, {0, 1, 0}, f);
  }
  return E;
}

Scene boxOverFloor(bool asMesh) {
  Scene s;
  addFloor(s);
  const int glow = addGlow(s, 1.5f);
  if (asMesh) {
    TriangleMesh m;
    for (const auto& f : boxFaces()) {
      const uint32_t base = uint32_t(m.positions.size());
      m.positions.insert(m.positions.end(), f.begin(), f.end());
      for (uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) m.indices.push_back(base + k);
    }
    m.material = glow;
    addMeshInstance(s, addMesh(s, m), Mat4::identity());
  } else {
    const Vec3 lo(-kBoxHalf, kBoxLo, -kBoxHalf), hi(kBoxHalf, kBoxHi, kBoxHalf);
    addShape(s, std::make_shared<Box>(lo, hi), Mat4::identity(), glow);
  }
  s.finalize();
  return s;
}

TEST(PathAreaLights, EmissiveBoxShapeLightsLikeTheSameBoxAsAMesh) {
  // Two estimators of one integral: the box's faces chosen by area, and the mesh's triangles
  // chosen by power, each MIS-combined with BSDF sampling. Both are unbiased, so both must
  // match the closed form and each other within noise. Tolerance: 4 standard errors (from the
  // samples' own variance; a false failure about once in 16000 runs were samples
  // independent, rarer with Sobol'), and the standard error is required to be under 0.5 % so
  // that the check stays sharper than what a wrong pdf or a missed face would cost (> 10 %).
  const int samples = 200000;
  for (Vec3 at : {Vec3(0.1f, 0, 0.2f), Vec3(1.2f, 0, -0.5f), Vec3(-2.0f, 0, 1.0f)}) {
    const double expected = kAlbedo / kPi * 1.5 * boxIrradiance(at);
    const Estimate shape = floorRadiance(boxOverFloor(false), at, samples);
    const Estimate mesh = floorRadiance(boxOverFloor(true), at, samples);
    EXPECT_LT(shape.stdError, 0.005 * expected) << "at x " << at.x;
    EXPECT_LT(mesh.stdError, 0.005 * expected) << "at x " << at.x;
    EXPECT_NEAR(shape.mean, expected, 4 * shape.stdError) << "at x " << at.x;
    EXPECT_NEAR(mesh.mean, expected, 4 * mesh.stdError) << "at x " << at.x;
    const double both = std::hypot(shape.stdError, mesh.stdError);
    EXPECT_NEAR(shape.mean, mesh.mean, 4 * both) << "at x " << at.x;
    std::printf("box at x %.1f: expected %.5f, shape %.5f +- %.5f, mesh %.5f +- %.5f\n", at.x,
                expected, shape.mean, shape.stdError, mesh.mean, mesh.stdError);
  }
}

}  // namespace
}  // namespace tray

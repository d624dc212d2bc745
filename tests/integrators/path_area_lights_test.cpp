// Area lights in the path tracer (NEE + MIS) against Lambert's polygon irradiance: a one-sided
// emitter whose vertex normals oppose its winding (glTF: the winding alone defines the front
// face).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

}  // namespace
}  // namespace tray

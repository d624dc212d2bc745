// KHR_materials_diffuse_transmission through the path tracer's Li: a thin black-based
// transmitter (a leaf, a lampshade) over an emitter of radiance 1, seen from the lit side's
// opposite. Nothing reflects, so the radiance is the transmitted single scattering:
//   L = dt colour x F,  F = the emitter's share of the cosine-weighted hemisphere below,
// F for a square of half-size a at distance h centred under the point being four corner
// rectangles of the point-to-parallel-rectangle view factor (Howell's catalogue, B-3):
//   F_corner = 1 / (2 pi) [A / sqrt(1 + A^2) atan(B / sqrt(1 + A^2)) + B / sqrt(1 + B^2)
//              atan(A / sqrt(1 + B^2))],  A = B = a / h.
// The transmitted ray does not change the medium (thin-walled).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/integrators/path_probe.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

double squareViewFactor(double halfSize, double distance) {
  const double a = halfSize / distance, s = std::sqrt(1 + a * a);
  return 4 * (2 * a / s * std::atan(a / s)) / (2 * kPi);
}

Color backLit(const Material& leaf, int samples) {
  Scene s;
  Material emitter = diffuse(Color(0.0f));
  emitter.emissive = Color(1.0f);
  addMeshInstance(s, addMesh(s, quadMesh(3.0f, addMaterial(s, emitter))),
                  Mat4::translate({0, -1, 0}));
  addMeshInstance(s, addMesh(s, quadMesh(20.0f, addMaterial(s, leaf))), Mat4::identity());
  s.finalize();
  PathProbe probe(s, 8);
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < samples; ++i) {
    Sampler sampler(3, uint32_t(i), 5, Sampler::Sequence::kIndependent);
    const Color L = probe.Li(Ray{{0.0f, 5, 0.0f}, {0, -1, 0}}, sampler);
    for (int k = 0; k < 3; ++k) sum[k] += L[k];
  }
  return {float(sum[0] / samples), float(sum[1] / samples), float(sum[2] / samples)};
}

TEST(PathDiffuseTransmission, BackLitLeafTransmitsTheClosedForm) {
  Material leaf = diffuse(Color(0.0f));
  leaf.doubleSided = true;
  leaf.layers.diffuseTransmission = 0.8f;
  leaf.layers.diffuseTransmissionColor = Color(0.25f, 0.75f, 0.5f);
  const Color L = backLit(leaf, 20000);
  const double F = squareViewFactor(3.0, 1.0);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(L[k], 0.8 * leaf.layers.diffuseTransmissionColor[k] * F, 0.01) << "channel " << k;
  // Without the extension the same leaf is black: the light seen is the transmitted light.
  Material opaque = diffuse(Color(0.0f));
  EXPECT_EQ(backLit(opaque, 64).y, 0.0f);
}

TEST(PathDiffuseTransmission, ReflectionAndTransmissionShareTheBase) {
  // A white base: the front sees nothing to reflect (the emitter is behind), so doubling dt
  // doubles the light through, and dt = 1 passes the emitter's light unchanged in colour.
  Material leaf = diffuse(Color(1.0f));
  leaf.layers.diffuseTransmission = 1.0f;
  const Color L = backLit(leaf, 20000);
  EXPECT_NEAR(L.x, squareViewFactor(3.0, 1.0), 0.01);
  EXPECT_NEAR(L.x, L.z, 1e-6f);
}

}  // namespace
}  // namespace tray

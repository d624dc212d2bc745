// KHR_materials_dispersion through the path tracer's Li: white light through a smooth glass
// slab at normal incidence. Each wavelength sees the slab's incoherent transmittance
//   T(n) = (1 - R)^2 / (1 - R^2) = (1 - R) / (1 + R),  R = ((n - 1) / (n + 1))^2,
// at n = n(lambda) (materials/dispersion.h), so each channel's expectation is the spectral
// integral sum_lambda response_c(lambda) T(n(lambda)); without dispersion it is T(n_d). The
// dispersive slab's mean matches the former within MC error and the non-dispersive result
// within MC error plus the (stated) spectral difference: no net colour shift.
#include <gtest/gtest.h>

#include <cmath>

#include "materials/dispersion.h"
#include "shapes/box.h"
#include "tests/integrators/path_probe.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

Material glass(float dispersion) {
  Material m;
  m.baseColor = Color(1.0f), m.metallic = 0, m.roughness = 0, m.transmission = 1, m.ior = 1.5f;
  m.layers.dispersion = dispersion;
  return m;
}

double slabT(double n) {
  const double R = (n - 1) * (n - 1) / ((n + 1) * (n + 1));
  return (1 - R) / (1 + R);
}

/// Mean radiance per channel, and the per-sample radiances' first channel (for comparisons).
/// `bystander`: a dispersive glass sphere off every path's way (paths here stay on one
/// vertical line).
Color radianceThroughSlab(float dispersion, int samples, std::vector<Color>* each = nullptr,
                          bool bystander = false) {
  Scene s;
  if (bystander) addSphere(s, {15, 10, 15}, 1.0f, addMaterial(s, glass(1.0f)));
  addShape(s, std::make_shared<Box>(Vec3(-20, 0, -20), Vec3(20, 3, 20)), Mat4::identity(),
           addMaterial(s, glass(dispersion)));
  Material emitter = diffuse(Color(0.0f));
  emitter.emissive = Color(1.0f);
  addMeshInstance(s, addMesh(s, quadMesh(50.0f, addMaterial(s, emitter))),
                  Mat4::translate({0, -1, 0}));
  s.finalize();
  PathProbe probe(s, 256);
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < samples; ++i) {
    Sampler sampler(7, uint32_t(i), 11, Sampler::Sequence::kSobol);
    const Color L = probe.Li(Ray{{0.1234f, 5, 0.0567f}, {0, -1, 0}}, sampler);
    if (each) each->push_back(L);
    for (int k = 0; k < 3; ++k) sum[k] += L[k];
  }
  return {float(sum[0] / samples), float(sum[1] / samples), float(sum[2] / samples)};
}

constexpr int kSamples = 65536;

TEST(PathDispersion, WhiteLightThroughASlabKeepsItsColour) {
  const float dispersion = 1.0f;  // Abbe number 20: strongly dispersive (flint-like and more)
  const Color L = radianceThroughSlab(dispersion, kSamples);
  const Color plain = radianceThroughSlab(0.0f, kSamples);
  double expected[3] = {0, 0, 0};
  for (float l = kWavelengthMin + 0.5f; l < kWavelengthMax; l += 1.0f) {
    const Color r = wavelengthResponse(l);
    const double t = slabT(dispersiveIor(1.5f, dispersion, l));
    for (int k = 0; k < 3; ++k) expected[k] += r[k] * t;
  }
  // A sample is 0 (reflected away) or about 1 times its channel weight (at most ~3): the
  // standard deviation of the mean is below 3 sqrt(T (1 - T) / N) = 2.5e-3; with Sobol'
  // strata much less. 3e-3 is a few of them.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(L[k], expected[k], 3e-3) << "channel " << k;
    // No net colour shift: each channel within MC error plus |T(n(lambda)) - T(n_d)| (< 0.004
    // here) of the non-dispersive slab.
    EXPECT_NEAR(L[k], plain[k], 7e-3) << "channel " << k;
    EXPECT_NEAR(plain[k], slabT(1.5), 3e-3);
  }
  std::printf("dispersive slab %.4f %.4f %.4f, spectral closed form %.4f %.4f %.4f, plain %.4f\n",
              L.x, L.y, L.z, expected[0], expected[1], expected[2], plain.x);
}

TEST(PathDispersion, PathsMissingDispersiveGlassKeepTheirBits) {
  // Dispersion 0 (the default: plain glass) draws no wavelength; a dispersive sphere that no
  // path meets changes no number of the others (the wavelength is drawn at a reserved sampler
  // dimension, only by paths that meet it).
  std::vector<Color> a, b;
  radianceThroughSlab(0.0f, 4096, &a);
  radianceThroughSlab(0.0f, 4096, &b, true);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x, b[i].x);
    EXPECT_EQ(a[i].z, b[i].z);
  }
}

TEST(PathDispersion, DispersiveSamplesVaryByWavelength) {
  // With dispersion the slab's per-sample radiance is a channel weight (colour varies per
  // sample), while the plain slab's samples are grey.
  std::vector<Color> d;
  radianceThroughSlab(1.0f, 256, &d);
  int coloured = 0;
  for (const Color& c : d)
    if (std::fabs(c.x - c.z) > 0.1f) ++coloured;
  EXPECT_GT(coloured, 128);
}

}  // namespace
}  // namespace tray

namespace tray {
namespace {

using namespace tray::test;

// A spectral reference: a ray through a dispersive glass sphere (radius 1) onto a thin
// emitting strip far behind it, traced in the test in double precision one wavelength at a
// time (1 nm steps: exact refraction and Fresnel at both crossings), against the path
// tracer's hero-wavelength estimate. The strip sees a narrow band of the spectrum: a
// saturated colour, where the clamp of the Rec.709 matching functions' negative lobes
// (materials/dispersion.h) matters most. The estimate must match the clamped curves' spectral
// integral within MC error; its distance from exact signed colorimetry is printed (docs).
struct D3 {
  double x, y, z;
};
D3 operator+(D3 a, D3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
D3 operator*(double s, D3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
double dot(D3 a, D3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

double fresnel(double cosI, double eta) {  // eta = n_t / n_i, unpolarised
  const double sin2T = (1 - cosI * cosI) / (eta * eta);
  if (sin2T >= 1) return 1;
  const double cosT = std::sqrt(1 - sin2T);
  const double rs = (cosI - eta * cosT) / (cosI + eta * cosT);
  const double rp = (eta * cosI - cosT) / (eta * cosI + cosT);
  return 0.5 * (rs * rs + rp * rp);
}

/// Refracts unit d at the unit normal n (facing against d), eta = n_t / n_i; the throughput
/// 1 - F is multiplied into t.
D3 refract(D3 d, D3 n, double eta, double& t) {
  const double cosI = -dot(d, n);
  t *= 1 - fresnel(cosI, eta);
  const double cosT = std::sqrt(1 - (1 - cosI * cosI) / (eta * eta));
  return (1 / eta) * d + (cosI / eta - cosT) * n;
}

/// Where the ray from o along d (+x heading) crosses the plane x = X, its y; throughput in t.
double throughSphere(double h, double n, double planeX, double& t) {
  t = 1;
  const D3 d0{1, 0, 0};
  const D3 p0{-std::sqrt(1 - h * h), h, 0};  // entry point on the unit sphere
  const D3 d1 = refract(d0, p0, n, t);
  const double s = -2 * dot(p0, d1);  // second intersection with |p| = 1
  const D3 p1 = p0 + s * d1;
  const D3 d2 = refract(d1, -1 * p1, 1 / n, t);
  return p1.y + (planeX - p1.x) / d2.x * d2.y;
}

TEST(PathDispersion, SphereSpectrumAgainstSpectralReference) {
  const float nd = 1.5f, dispersion = 1.0f;
  const double h = 0.5, planeX = 10, y0 = -3.40, y1 = -3.37;  // 490-520 nm land on it
  Scene s;
  Material g;
  g.baseColor = Color(1.0f), g.metallic = 0, g.roughness = 0, g.transmission = 1, g.ior = nd;
  g.layers.dispersion = dispersion;
  addSphere(s, {0, 0, 0}, 1.0f, addMaterial(s, g));
  Material emitter = diffuse(Color(0.0f));
  emitter.emissive = Color(1.0f);
  // Thin in x: rays also enter through its top face, over y1 - 0.0002 tan(21 deg) < 1e-4.
  addShape(s,
           std::make_shared<Box>(Vec3(float(planeX), float(y0), -5),
                                 Vec3(float(planeX) + 2e-4f, float(y1), 5)),
           Mat4::identity(), addMaterial(s, emitter));
  s.finalize();
  // The reference, per nm: exact (signed) and clamped responses.
  double clamped[3] = {0, 0, 0}, exact[3] = {0, 0, 0};
  for (float l = kWavelengthMin + 0.5f; l < kWavelengthMax; l += 1.0f) {
    double t;
    const double y = throughSphere(h, dispersiveIor(nd, dispersion, l), planeX, t);
    if (y < y0 || y > y1) continue;
    const Color r = wavelengthResponse(l), e = wavelengthResponseSigned(l);
    for (int k = 0; k < 3; ++k) clamped[k] += t * r[k], exact[k] += t * e[k];
  }
  PathProbe probe(s, 16);
  const int n = 65536;
  double sum[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) {
    Sampler sampler(3, uint32_t(i), 5, Sampler::Sequence::kSobol);
    const Color L = probe.Li(Ray{{-5, float(h), 0}, {1, 0, 0}}, sampler);
    for (int k = 0; k < 3; ++k) sum[k] += L[k];
  }
  std::printf(
      "sphere band: render %.4f %.4f %.4f, clamped ref %.4f %.4f %.4f, exact ref %.4f "
      "%.4f %.4f\n",
      sum[0] / n, sum[1] / n, sum[2] / n, clamped[0], clamped[1], clamped[2], exact[0], exact[1],
      exact[2]);
  ASSERT_GT(clamped[0] + clamped[1] + clamped[2], 0.05);  // the strip sees some of the spectrum
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / n, clamped[k], 0.01 + 0.03 * clamped[k]) << k;
}

}  // namespace
}  // namespace tray

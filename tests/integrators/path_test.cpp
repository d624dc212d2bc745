#include "integrators/path.h"

#include <gtest/gtest.h>

#include "accel/registry.h"
#include "materials/bsdf.h"
#include "materials/medium_stack.h"
#include "render/renderer.h"
#include "tests/integrators/path_probe.h"
#include "tests/integrators/path_under_test.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

Film render(const Scene& scene, const CameraDesc& cam, int w, int h, RenderSettings settings,
            int threads = 0, RenderStats* stats = nullptr) {
  settings.set("integrator", test::pathUnderTest());
  return renderFilm(scene, cam, w, h, settings, stats, {}, "embree", threads);
}

// --- White furnace: a convex diffuse object under a uniform environment --------------------

class WhiteFurnace : public ::testing::TestWithParam<float> {};

TEST_P(WhiteFurnace, EveryPixelIsAlbedoTimesEnvironment) {
  // A convex object sees only the environment, so L = albedo x 1 on the sphere and 1 off it,
  // whatever the depth beyond 2. Light sampling and BSDF sampling are both used and MIS-
  // weighted, so a wrong weight or pdf shows as a pixel off by much more than the noise.
  const float albedo = GetParam();
  Scene s;
  addSphere(s, {0, 0, 0}, 1.0f, addMaterial(s, diffuse(Color(albedo))));
  s.environment.background = Color(1.0f);
  s.finalize();
  RenderSettings st;
  st.set("spp", 256);
  st.set("max-depth", 100);
  RenderStats stats;
  Film f = render(s, lookAt({0, 0, 3}, {0, 0, 0}, 0.5f), 8, 8, st, 0, &stats);
  int onSphere = 0;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const float* p = f.pixel(Film::kBeauty, x, y);
      // Pixel coverage of the silhouette mixes both values: the expectation is alpha-weighted.
      float expected = p[3] * albedo + (1 - p[3]) * 1.0f;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], expected, 0.01f) << x << "," << y;
      onSphere += p[3] == 1.0f;
    }
  EXPECT_GT(onSphere, 30);
  EXPECT_EQ(stats.rays.nanSamples, 0u);
  EXPECT_GT(stats.rays.shadowRays, 0u);
}

INSTANTIATE_TEST_SUITE_P(Albedo, WhiteFurnace, ::testing::Values(1.0f, 0.5f));

// --- Direct light from an emissive sphere, analytic ------------------------------------------

TEST(Path, DiffuseFloorUnderSphereLightMatchesAnalyticIrradiance) {
  // A point straight below a sphere of radiance Le, radius r, centre distance d receives
  // E = pi Le (r/d)^2 (a uniform sphere looks like a point source of intensity pi r^2 Le
  // along the axis), so the floor reflects albedo Le (r/d)^2. max depth 2: direct only.
  Scene s;
  const float albedo = 0.6f, r = 0.5f, d = 2.0f;
  const Color Le(3.0f, 2.0f, 1.0f);
  int floor = addMaterial(s, diffuse(Color(albedo)));
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Le;
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), floor);
  addSphere(s, {0, d, 0}, r, addMaterial(s, glow));
  s.finalize();
  PathProbe probe(s, 2);
  double sum = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    Sampler sampler(7, uint32_t(i), 1);
    sum += probe.Li(Ray{{0.3f, 0.4f, 0}, normalize(Vec3(-0.3f, -0.4f, 0))}, sampler).x;
  }
  double expected = albedo * Le.x * (r / d) * (r / d);
  EXPECT_NEAR(sum / n, expected, 0.01 * expected);
  EXPECT_EQ(probe.stats.shadowRays, uint64_t(n));
}

// --- Nested dielectrics ---------------------------------------------------------------------

/// Refraction of unit d through unit n (facing d's origin side) from index n1 to n2, in double:
/// an independent statement of Snell's law in vector form.
void snell(const double d[3], const double n[3], double n1, double n2, double out[3]) {
  double cosI = -(d[0] * n[0] + d[1] * n[1] + d[2] * n[2]);
  double eta = n1 / n2, sin2T = eta * eta * (1 - cosI * cosI), cosT = std::sqrt(1 - sin2T);
  for (int k = 0; k < 3; ++k) out[k] = eta * d[k] + (eta * cosI - cosT) * n[k];
}

TEST(Path, RayThroughConcentricSpheresFollowsSnellAtEveryInterface) {
  // Glass (1.5) filled with water (1.33) holding an air bubble (1.0): the relative IOR at
  // each crossing comes from the medium stack. Walk the path with the integrator's pieces
  // (accelerator, MediumStack, Bsdf sampling forced to refract) and compare every direction
  // with Snell's law evaluated in double with the known indices.
  Scene s;
  auto glassLike = [](float ior) {
    Material m;
    m.metallic = 0, m.roughness = 0, m.transmission = 1, m.ior = ior;
    return m;
  };
  const float radii[3] = {1.0f, 0.6f, 0.3f}, iors[3] = {1.5f, 1.33f, 1.0f};
  for (int i = 0; i < 3; ++i) addSphere(s, {0, 0, 0}, radii[i], addMaterial(s, glassLike(iors[i])));
  s.finalize();
  auto accel = makeAccelerator("embree", s);

  Ray ray{{-3, 0.2f, 0}, {1, 0, 0}};
  double d[3] = {1, 0, 0}, o[3] = {-3, 0.2, 0};
  // Expected index sequence along the ray: in through 3 surfaces, out through 3.
  const double seq[7] = {1.0, 1.5, 1.33, 1.0, 1.33, 1.5, 1.0};
  MediumStack media;
  for (int crossing = 0; crossing < 6; ++crossing) {
    Hit hit;
    ASSERT_TRUE(accel->intersect(ray, hit)) << crossing;
    SurfacePoint sp = s.surface(ray, hit);
    const Material& m = s.material(sp.material);
    MediumStack::Interface iface = media.interface(sp.material, m, sp.frontFace);
    ASSERT_TRUE(iface.real);
    EXPECT_FLOAT_EQ(iface.etaI, float(seq[crossing])) << crossing;
    EXPECT_FLOAT_EQ(iface.etaT, float(seq[crossing + 1])) << crossing;
    Vec3 n = sp.frontFace ? sp.n : -sp.n;
    Bsdf bsdf(m, n, iface.etaT / iface.etaI);
    BsdfSample bs = bsdf.sample(-ray.d, 0.99999f, {0.5f, 0.5f});
    ASSERT_TRUE(bs.valid() && bs.transmission && bs.delta) << crossing;
    media.cross(sp.material, m, sp.frontFace);

    // The same crossing in double: exact sphere hit, then Snell.
    double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
    double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
    double r = sp.material == 0 ? 1.0 : (sp.material == 1 ? 0.6 : 0.3);
    double disc = b * b - (c - r * r),
           t = sp.frontFace ? -b - std::sqrt(disc) : -b + std::sqrt(disc);
    double p[3], nn[3], out[3];
    for (int k = 0; k < 3; ++k) p[k] = o[k] + t * d[k], nn[k] = p[k] / r * (sp.frontFace ? 1 : -1);
    snell(d, nn, seq[crossing], seq[crossing + 1], out);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(bs.wi[k], out[k], 2e-5) << "crossing " << crossing << " axis " << k;
      o[k] = p[k], d[k] = out[k];
    }
    ray = spawnRay(sp.p, sp.ng, bs.wi, 0.0f);
  }
  EXPECT_EQ(media.size(), 0);
  // Concentric shells: the outgoing ray is the incoming one rotated, and leaves at 1.0 index.
  EXPECT_NEAR(length(ray.d), 1.0f, 1e-5f);
}

// --- Robustness and determinism ---------------------------------------------------------------

Scene mixedScene() {
  Scene s;
  int white = addMaterial(s, diffuse(Color(0.7f)));
  Material metal;
  metal.baseColor = Color(0.9f, 0.6f, 0.3f), metal.metallic = 1, metal.roughness = 0.3f;
  Material mirror = metal;
  mirror.roughness = 0;
  Material glass;
  glass.metallic = 0, glass.roughness = 0, glass.transmission = 1, glass.ior = 1.5f;
  Material frosted = glass;
  frosted.roughness = 0.4f;
  Material light = diffuse(Color(0.5f));
  light.emissive = Color(8.0f);
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), white);
  addSphere(s, {-1.5f, 0.6f, 0}, 0.6f, addMaterial(s, metal));
  addSphere(s, {0, 0.6f, 0}, 0.6f, addMaterial(s, glass));
  addSphere(s, {1.5f, 0.6f, 0}, 0.6f, addMaterial(s, frosted));
  addSphere(s, {0, 0.3f, 1.2f}, 0.3f, addMaterial(s, mirror));
  addSphere(s, {0, 3, 1}, 0.4f, addMaterial(s, light));
  uint32_t quad = addMesh(s, quadMesh(0.5f, addMaterial(s, light)));
  addMeshInstance(s, quad, Mat4::translate({2, 3, -1}) * Mat4::scale({1, -1, 1}));  // faces down
  PunctualLightDesc spot;
  spot.type = PunctualLightDesc::Type::kSpot;
  spot.position = {-2, 3, 2};
  spot.direction = normalize(Vec3(0.5f, -1, -0.5f));
  spot.intensity = Color(20.0f);
  s.lights.push_back(spot);
  s.lights.push_back(pointLight({2, 2, 2}, Color(5.0f)));
  PunctualLightDesc sun;
  sun.type = PunctualLightDesc::Type::kDirectional;
  sun.direction = normalize(Vec3(1, -2, -1));
  sun.intensity = Color(1.0f);
  s.lights.push_back(sun);
  s.environment.background = Color(0.1f, 0.2f, 0.3f);
  s.finalize();
  return s;
}

TEST(Path, SameImageForOneAndTwoThreadsAndNoNaN) {
  Scene s = mixedScene();
  RenderSettings st;
  st.set("spp", 4);
  CameraDesc cam = lookAt({0, 2, 5}, {0, 0.5f, 0});
  RenderStats a, b;
  Film one = render(s, cam, 40, 30, st, 1, &a), two = render(s, cam, 40, 30, st, 2, &b);
  EXPECT_EQ(one.layers()[0].data, two.layers()[0].data);
  EXPECT_EQ(a.rays.total(), b.rays.total());
  EXPECT_EQ(a.rays.nanSamples, 0u);
  EXPECT_GT(a.rays.shadowRays, 0u);
  EXPECT_GT(a.rays.secondaryRays, 0u);
}

TEST(Path, MaxDepthOneShowsOnlyEmittersAndEnvironment) {
  // Mitsuba's convention: depth 1 = directly visible emitters (and the environment) only.
  Scene s = mixedScene();
  RenderSettings st;
  st.set("max-depth", 1);
  RenderStats stats;
  Film f = render(s, lookAt({0, 2, 5}, {0, 0.5f, 0}), 20, 15, st, 0, &stats);
  EXPECT_EQ(stats.rays.shadowRays, 0u);
  EXPECT_EQ(stats.rays.secondaryRays, 0u);
  for (int y = 0; y < 15; ++y)
    for (int x = 0; x < 20; ++x) {
      const float* p = f.pixel(Film::kBeauty, x, y);
      bool env = p[0] == 0.1f && p[1] == 0.2f && p[2] == 0.3f;
      bool black = p[0] == 0 && p[1] == 0 && p[2] == 0;
      bool light = p[0] == 8.0f;
      EXPECT_TRUE(env || black || light) << x << "," << y << ": " << p[0];
    }
}

}  // namespace
}  // namespace tray

#include "integrators/whitted.h"

#include <gtest/gtest.h>

#include <optional>

#include "accel/registry.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

struct Rendered {
  Film film;
  RenderStats stats;
};

Rendered render(const Scene& scene, const CameraDesc& cam, int w, int h,
                RenderSettings settings = {}, int threads = 0) {
  RenderStats st;
  Film film = renderFilm(scene, cam, w, h, settings, &st, {}, "embree", threads);
  return {std::move(film), st};
}

Color pixel(const Film& f, int x, int y) {
  const float* p = f.pixel(Film::kBeauty, x, y);
  return {p[0], p[1], p[2]};
}

// --- Analytic check: a Phong sphere under one point light --------------------------------

TEST(Whitted, SphereUnderPointLightMatchesPhongFormula) {
  Scene s;
  Material m = diffuse(Color(0.6f, 0.4f, 0.2f));
  m.phong.specular = Color(0.3f);
  m.phong.shininess = 20.0f;
  int mat = addMaterial(s, m);
  addSphere(s, {0, 0, 0}, 1.0f, mat);
  const Vec3 lightPos{3, 4, 5};
  const Color I{50, 40, 30};
  s.lights.push_back(pointLight(lightPos, I));
  s.finalize();
  const int W = 64, H = 64;
  CameraDesc cam = lookAt({0, 0, 5}, {0, 0, 0}, 0.6f);
  Rendered r = render(s, cam, W, H);
  auto camera = Camera::create(cam, W, H);

  int checked = 0;
  for (int y = 8; y < H; y += 7)
    for (int x = 8; x < W; x += 7) {
      // Independent reference in double: ray-sphere, then the formula of phongDirect.
      Ray ray = camera->generateRay(x + 0.5f, y + 0.5f);
      double ox = ray.o.x, oy = ray.o.y, oz = ray.o.z, dx = ray.d.x, dy = ray.d.y, dz = ray.d.z;
      double b = ox * dx + oy * dy + oz * dz, c = ox * ox + oy * oy + oz * oz - 1.0;
      double disc = b * b - c;
      Color got = pixel(r.film, x, y);
      if (disc < 1e-3) {  // skip the silhouette, where pixel and reference may disagree
        if (disc < -1e-3) {
          EXPECT_EQ(got, Color(0.0f)) << x << "," << y;
        }
        continue;
      }
      double t = -b - std::sqrt(disc);
      double px = ox + t * dx, py = oy + t * dy, pz = oz + t * dz;  // = normal on a unit sphere
      double lx = lightPos.x - px, ly = lightPos.y - py, lz = lightPos.z - pz;
      double d2 = lx * lx + ly * ly + lz * lz, dl = std::sqrt(d2);
      lx /= dl, ly /= dl, lz /= dl;
      double cosI = px * lx + py * ly + pz * lz;
      double expected[3] = {0, 0, 0};
      if (cosI > 0) {
        double rx = 2 * cosI * px - lx, ry = 2 * cosI * py - ly, rz = 2 * cosI * pz - lz;
        double cosR = std::max(0.0, -(rx * dx + ry * dy + rz * dz));
        double spec = 0.3 * (20.0 + 2) / (2 * M_PI) * std::pow(cosR, 20.0);
        double kd[3] = {0.6, 0.4, 0.2}, Ic[3] = {50, 40, 30};
        for (int k = 0; k < 3; ++k) expected[k] = (kd[k] / M_PI + spec) * Ic[k] / d2 * cosI;
      }
      EXPECT_NEAR(got.x, expected[0], 1e-3) << x << "," << y;
      EXPECT_NEAR(got.y, expected[1], 1e-3) << x << "," << y;
      EXPECT_NEAR(got.z, expected[2], 1e-3) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 20);
}

// --- Shadows -------------------------------------------------------------------------------

TEST(Whitted, SphereCastsShadowOnFloor) {
  Scene s;
  int mat = addMaterial(s, diffuse(Color(0.5f)));
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), mat);
  addSphere(s, {0, 1.5f, 0}, 0.5f, mat);
  s.lights.push_back(pointLight({0, 4, 0}, Color(16.0f)));
  s.finalize();
  const PreparedScene prepared(s, lookAt({0, 6, 0.01f}, {0, 0, 0}), {8, 8});
  const RenderContext ctx = prepared.context(RenderSettings{});
  auto whitted = makeWhitted(ctx);
  Sampler sampler(0, 0, 0);
  RayStats stats;
  // Straight below the sphere: in shadow. Off to the side (x = 3): lit by E cos / pi * kd.
  Color shadowed = whitted->Li(Ray{{0.01f, 0.9f, 0}, {0, -1, 0}}, sampler, stats, nullptr);
  EXPECT_EQ(shadowed, Color(0.0f));
  Color lit = whitted->Li(Ray{{3, 0.9f, 0}, {0, -1, 0}}, sampler, stats, nullptr);
  float d2 = 9 + 16, cosI = 4 / std::sqrt(d2);
  EXPECT_NEAR(lit.x, 0.5f / kPi * 16.0f / d2 * cosI, 1e-5f);
  EXPECT_GE(stats.shadowRays, 2u);
}

// --- Mirror reflection ---------------------------------------------------------------------

TEST(Whitted, MirrorReflectsEmitterScaledByReflectance) {
  Scene s;
  Material mirror = diffuse(Color(0.0f));
  mirror.phong.reflectance = 0.5f;
  int mm = addMaterial(s, mirror);
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(1, 2, 3);
  int gm = addMaterial(s, glow);
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), mm);
  addSphere(s, {2, 1, 0}, 0.5f, gm);  // a ray from (0,1,0) towards (1,0,0) bounces to it
  s.environment.background = Color(0.1f, 0.2f, 0.3f);
  s.finalize();
  const PreparedScene prepared(s, lookAt({0, 1, 5}, {0, 0, 0}), {8, 8});
  const RenderContext ctx = prepared.context(RenderSettings{});
  auto whitted = makeWhitted(ctx);
  Sampler sampler(0, 0, 0);
  RayStats stats;
  Color viaMirror = whitted->Li(Ray{{0, 1, 0}, normalize(Vec3(1, -1, 0))}, sampler, stats, nullptr);
  EXPECT_NEAR(viaMirror.x, 0.5f, 1e-5f);
  EXPECT_NEAR(viaMirror.z, 1.5f, 1e-5f);
  Color sky = whitted->Li(Ray{{0, 1, 0}, normalize(Vec3(-1, -1, 0))}, sampler, stats, nullptr);
  EXPECT_NEAR(sky.y, 0.1f, 1e-6f);  // reflected background, halved
}

// --- Refraction and total internal reflection ----------------------------------------------

struct GlassSphere {
  Scene scene;
  std::optional<PreparedScene> prepared;
  std::unique_ptr<Integrator> whitted;
  explicit GlassSphere(int maxDepth) {
    Material glass = diffuse(Color(0.0f));
    glass.phong.transmittance = 1.0f;
    glass.ior = 1.5f;
    addSphere(scene, {0, 0, 0}, 1.0f, addMaterial(scene, glass));
    scene.environment.background = Color(1.0f, 0.5f, 0.25f);
    scene.finalize();
    prepared.emplace(scene, lookAt({0, 0, 5}, {0, 0, 0}), ImageSize{4, 4});
    RenderSettings st;
    st.set("max-depth", maxDepth);
    whitted = makeWhitted(prepared->context(st));
  }
};

TEST(Whitted, RayBeyondCriticalAngleIsTrappedUntilMaxDepth) {
  GlassSphere g(7);
  Sampler sampler(0, 0, 0);
  // Inside the sphere, 0.9 off-centre: incidence asin(0.9) = 64 deg > critical 41.8 deg, and a
  // sphere keeps that angle at every bounce, so the light can never leave.
  RayStats trapped;
  Color L = g.whitted->Li(Ray{{0, 0.9f, 0}, {1, 0, 0}}, sampler, trapped, nullptr);
  EXPECT_EQ(L, Color(0.0f));
  EXPECT_EQ(trapped.secondaryRays, 7u);
  // 0.3 off-centre: incidence 17.5 deg, refracts out into the background.
  RayStats escapes;
  Color out = g.whitted->Li(Ray{{0, 0.3f, 0}, {1, 0, 0}}, sampler, escapes, nullptr);
  EXPECT_NEAR(out.x, 1.0f, 1e-6f);
  EXPECT_EQ(escapes.secondaryRays, 1u);
}

TEST(Whitted, RefractionFollowsSnell) {
  Vec3 d = normalize(Vec3(1, -1, 0)), n{0, 1, 0}, t;
  ASSERT_TRUE(refract(d, n, 1.0f / 1.5f, t));
  float sinI = std::sqrt(0.5f), sinT = std::sqrt(t.x * t.x + t.z * t.z);
  EXPECT_NEAR(sinT, sinI / 1.5f, 1e-6f);
  EXPECT_FALSE(refract(normalize(Vec3(1, -0.5f, 0)), n, 1.5f, t));  // 63 deg from glass: TIR
}

// --- Robust ray offsets: no acne at any scale ---------------------------------------------

/// A lit floor with a sphere on it, scaled by `scale` and moved by `offset`; light intensity
/// scales with scale^2 so irradiance is unchanged.
size_t shadowedPixels(float scale, Vec3 offset, bool meshFloor) {
  Scene s;
  int mat = addMaterial(s, diffuse(Color(0.8f)));
  if (meshFloor) {
    addMeshInstance(s, addMesh(s, quadMesh(4.0f, mat)),
                    Mat4::translate(offset) * Mat4::scale(Vec3(scale)));
  } else {
    addShape(s, std::make_shared<Plane>(), Mat4::translate(offset) * Mat4::scale(Vec3(scale)), mat);
  }
  addShape(s, std::make_shared<Sphere>(1.0f),
           Mat4::translate(offset + scale * Vec3(0, 1, 0)) * Mat4::scale(Vec3(scale)), mat);
  s.lights.push_back(pointLight(offset + scale * Vec3(2, 5, 1), Color(30.0f * scale * scale)));
  s.finalize();
  CameraDesc cam = lookAt(offset + scale * Vec3(0, 4, 6), offset, 0.9f);
  Rendered r = render(s, cam, 96, 72);
  size_t dark = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      const float* p = r.film.pixel(Film::kBeauty, x, y);
      if (p[3] > 0 && p[0] < 0.02f) ++dark;
    }
  return dark;
}

class WhittedScale : public ::testing::TestWithParam<bool> {};

TEST_P(WhittedScale, NoShadowAcneFromMillimetresToKilometres) {
  bool mesh = GetParam();
  size_t reference = shadowedPixels(1.0f, Vec3(0.0f), mesh);
  ASSERT_GT(reference, 50u);  // the sphere's shadow and its unlit half exist
  for (float scale : {1e-3f, 1e4f}) {
    size_t n = shadowedPixels(scale, Vec3(0.0f), mesh);
    EXPECT_NEAR(double(n), double(reference), 0.001 * reference + 1) << "scale " << scale;
  }
  size_t far = shadowedPixels(1.0f, Vec3(1e5f, 0, 1e5f), mesh);
  EXPECT_NEAR(double(far), double(reference), 0.001 * reference + 1) << "moved 1e5";
}

INSTANTIATE_TEST_SUITE_P(FloorKinds, WhittedScale, ::testing::Values(false, true),
                         [](const auto& info) {
                           return info.param ? "MeshFloor" : "AnalyticPlane";
                         });

// --- Determinism ---------------------------------------------------------------------------

TEST(Whitted, SameImageForOneAndTwoThreads) {
  Scene s;
  int mat = addMaterial(s, diffuse(Color(0.7f)));
  addShape(s, std::make_shared<Plane>(), Mat4::identity(), mat);
  addSphere(s, {0, 1, 0}, 1.0f, mat);
  s.lights.push_back(pointLight({2, 5, 2}, Color(40.0f)));
  s.finalize();
  RenderSettings st;
  st.set("spp", 4);
  st.set("pixel-sampler", "jitter");
  CameraDesc cam = lookAt({0, 3, 6}, {0, 0.5f, 0});
  Rendered a = render(s, cam, 48, 32, st, 1), b = render(s, cam, 48, 32, st, 2);
  EXPECT_EQ(a.film.layers()[0].data, b.film.layers()[0].data);
  EXPECT_EQ(a.stats.rays.total(), b.stats.rays.total());
}

}  // namespace
}  // namespace tray

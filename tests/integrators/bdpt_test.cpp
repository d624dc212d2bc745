// Bidirectional path tracing (integrators/bdpt.cpp): its image's mean against path's for every
// light kind, the white furnace, media; each strategy family alone converging to the same
// image; the MIS weights of a path summing to 1 over its strategies; bit-identical renders for
// any thread count and regions that stitch; what it refuses, in one line each.
#include "integrators/bdpt.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "bench/sky_maps.h"
#include "core/error.h"
#include "integrators/bdpt_tracer.h"
#include "tests/error_of.h"
#include "tests/integrators/render_job.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

/// A rotation by `angle` about +X (a quaternion).
Mat4 rotateX(float angle) {
  return Mat4::rotate(std::sin(0.5f * angle), 0.0f, 0.0f, std::cos(0.5f * angle));
}

enum class LightKind { kArea, kSphere, kPoint, kSpot, kDirectional, kConstant, kImage };

/// A floor, a back wall and a diffuse ball lit by one light of the given kind; with `glass`, a
/// second ball of absorbing glass (KHR_materials_volume) holding a smaller ball of water.
Scene room(LightKind kind, bool glass = false, const std::function<void(Scene&)>& extra = {}) {
  Scene s;
  const int floor = addMaterial(s, diffuse(Color(0.6f, 0.5f, 0.4f)));
  addMeshInstance(s, addMesh(s, quadMesh(3, floor)), Mat4::identity());
  addMeshInstance(s, addMesh(s, quadMesh(3, floor)),
                  Mat4::translate({0, 3, -2}) * rotateX(kPi / 2));
  addSphere(s, {0.8f, 0.6f, 0}, 0.6f, addMaterial(s, diffuse(Color(0.3f, 0.6f, 0.8f))));
  if (glass) {
    Material g = diffuse(Color(1.0f));
    g.metallic = 0, g.roughness = 0, g.transmission = 1, g.ior = 1.5f;
    g.layers.attenuationColor = Color(0.5f, 0.8f, 0.9f), g.layers.attenuationDistance = 1.0f;
    addSphere(s, {-0.9f, 0.7f, 0.3f}, 0.7f, addMaterial(s, g));
    Material w = g;
    w.ior = 1.33f, w.layers.attenuationColor = Color(0.9f), w.priority = 1;
    addSphere(s, {-0.9f, 0.7f, 0.3f}, 0.3f, addMaterial(s, w));
  }
  Material glow = diffuse(Color(0.0f));
  glow.emissive = Color(6.0f, 5.0f, 4.0f);
  switch (kind) {
    case LightKind::kArea:  // a one-sided quad facing down
      addMeshInstance(s, addMesh(s, quadMesh(0.7f, addMaterial(s, glow))),
                      Mat4::translate({0, 2.5f, 0}) * rotateX(kPi));
      break;
    case LightKind::kSphere:
      addSphere(s, {-0.5f, 2.2f, 0.5f}, 0.3f, addMaterial(s, glow));
      break;
    case LightKind::kPoint:
      s.lights.push_back(pointLight({0.5f, 2.5f, 1}, Color(12.0f, 10.0f, 8.0f)));
      break;
    case LightKind::kSpot:
      s.lights.push_back(
          spotLight({-0.5f, 2.5f, 0.5f}, {0.2f, -1, -0.1f}, Color(20.0f), 0.3f, 0.7f));
      break;
    case LightKind::kDirectional:
      s.lights.push_back(directionalLight({0.3f, -1, -0.4f}, Color(2.0f, 1.8f, 1.5f)));
      break;
    case LightKind::kConstant:
      s.environment.background = Color(0.8f, 0.9f, 1.0f);
      break;
    case LightKind::kImage:
      s.environment.map = maps::hemispheres(64, 32, Color(2.0f, 1.6f, 1.2f), Color(0.2f));
      break;
  }
  if (extra) extra(s);
  s.cameras.push_back(lookAt({0.3f, 1.6f, 4.5f}, {0, 0.8f, 0}, 0.9f));
  s.finalize();
  return s;
}

RenderSettings settings(const std::string& integrator, int spp, int maxDepth,
                        const std::string& strategy = "all") {
  RenderSettings s;
  s.set("integrator", integrator);
  s.set("spp", spp);
  s.set("max-depth", maxDepth);
  if (integrator == "bdpt") s.set("bdpt-strategy", strategy);
  return s;
}

Film renderOf(const Scene& scene, const RenderSettings& s, int size = 32, int threads = 0) {
  return renderFilm(scene, scene.cameras.at(0), size, size, s, nullptr, {}, "embree", threads);
}

Color meanOf(const Film& f) { return meanBeauty(f); }

void expectMeansClose(const Color& a, const Color& b, float tolerance, const std::string& what) {
  std::printf("%-32s bdpt/path %.4f %.4f %.4f\n", what.c_str(), a.x / b.x, a.y / b.y, a.z / b.z);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(a[c] / b[c], 1.0f, tolerance)
        << what << " channel " << c << ": " << a[c] << " against " << b[c];
}

// --- Against path, whose estimator is tested against closed forms ---------------------------

TEST(Bdpt, MeanMatchesPathForEveryLightKind) {
  const struct {
    LightKind kind;
    const char* name;
  } kinds[] = {{LightKind::kArea, "area quad"},  {LightKind::kSphere, "emissive sphere"},
               {LightKind::kPoint, "point"},     {LightKind::kSpot, "spot"},
               {LightKind::kDirectional, "sun"}, {LightKind::kConstant, "constant sky"},
               {LightKind::kImage, "image sky"}};
  for (const auto& k : kinds) {
    const Scene s = room(k.kind);
    const Color bdpt = meanOf(renderOf(s, settings("bdpt", 64, 4)));
    const Color path = meanOf(renderOf(s, settings("path-scalar", 256, 4)));
    std::printf("%-16s bdpt %.5f %.5f %.5f  path %.5f %.5f %.5f\n", k.name, bdpt.x, bdpt.y, bdpt.z,
                path.x, path.y, path.z);
    expectMeansClose(bdpt, path, 0.02f, k.name);
  }
}

TEST(Bdpt, NestedAbsorbingDielectricsMatchPath) {
  const Scene s = room(LightKind::kArea, true);
  const Color bdpt = meanOf(renderOf(s, settings("bdpt", 64, 8)));
  const Color path = meanOf(renderOf(s, settings("path-scalar", 256, 8)));
  expectMeansClose(bdpt, path, 0.03f, "glass and water");
}

TEST(Bdpt, AlphaGlossyAndUnlitMatchPath) {
  // A half-transparent sheet (BLEND) between the light and the floor, a rough metal ball, a
  // clearcoated one and an unlit panel (found by the camera only).
  const Scene s = room(LightKind::kArea, false, [](Scene& s) {
    Material sheet = diffuse(Color(0.9f, 0.3f, 0.2f));
    sheet.alphaMode = AlphaMode::kBlend, sheet.alpha = 0.4f, sheet.doubleSided = true;
    addMeshInstance(s, addMesh(s, quadMesh(0.8f, addMaterial(s, sheet))),
                    Mat4::translate({-0.3f, 1.6f, 0.2f}));
    Material metal = diffuse(Color(0.9f, 0.7f, 0.4f));
    metal.metallic = 1, metal.roughness = 0.3f;
    addSphere(s, {-1.6f, 0.4f, 0.8f}, 0.4f, addMaterial(s, metal));
    Material coated = diffuse(Color(0.2f, 0.5f, 0.2f));
    coated.layers.clearcoat = 1, coated.layers.clearcoatRoughness = 0.1f;
    addSphere(s, {1.8f, 0.4f, 1.0f}, 0.4f, addMaterial(s, coated));
    Material panel = diffuse(Color(0.3f, 0.6f, 0.9f));
    panel.unlit = true;
    addMeshInstance(s, addMesh(s, quadMesh(0.3f, addMaterial(s, panel))),
                    Mat4::translate({2.0f, 1.5f, -1.9f}) * rotateX(kPi / 2));
  });
  const Color bdpt = meanOf(renderOf(s, settings("bdpt", 64, 5)));
  const Color path = meanOf(renderOf(s, settings("path-scalar", 256, 5)));
  expectMeansClose(bdpt, path, 0.02f, "alpha, metal, clearcoat, unlit");
}

TEST(Bdpt, WhiteFurnace) {
  // A diffuse ball of albedo 0.8 under a uniform sky of radiance 1: a convex body sees only
  // the sky, so the ball shows 0.8 and the sky 1 (every strategy, the light tracing's too).
  Scene s;
  addSphere(s, {0, 0, 0}, 1.0f, addMaterial(s, diffuse(Color(0.8f))));
  s.environment.background = Color(1.0f);
  s.cameras.push_back(lookAt({0, 0, 3.2f}, {0, 0, 0}, 0.8f));
  s.finalize();
  const Film f = renderOf(s, settings("bdpt", 64, 8));
  double ball = 0, sky = 0;
  int nBall = 0, nSky = 0;
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x) {
      const float dx = (x + 0.5f) / f.width() - 0.5f, dy = (y + 0.5f) / f.height() - 0.5f;
      const float r = std::sqrt(dx * dx + dy * dy);  // the ball: radius ~0.37 of the image
      const float v = f.pixel(Film::kBeauty, x, y)[1];
      if (r < 0.3f) ball += v, ++nBall;
      if (r > 0.45f) sky += v, ++nSky;
    }
  EXPECT_NEAR(ball / nBall, 0.8, 0.01);
  EXPECT_NEAR(sky / nSky, 1.0, 1e-5);
}

// --- Each strategy family alone (Veach 1997 §10.3.5's check) ---------------------------------

TEST(Bdpt, EachStrategyFamilyConvergesToPathsImage) {
  const Scene s = room(LightKind::kArea);
  const Color path = meanOf(renderOf(s, settings("path-scalar", 256, 3)));
  for (const char* family : {"s0", "s1", "t1"}) {
    const Color one = meanOf(renderOf(s, settings("bdpt", 128, 3, family)));
    expectMeansClose(one, path, 0.03f, family);
  }
  // And per pixel: light tracing alone against next-event estimation alone, 16x16.
  const Film nee = renderOf(s, settings("bdpt", 256, 3, "s1"), 16);
  const Film light = renderOf(s, settings("bdpt", 256, 3, "t1"), 16);
  double err = 0, norm = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const double a = nee.pixel(Film::kBeauty, x, y)[0], b = light.pixel(Film::kBeauty, x, y)[0];
      err += (a - b) * (a - b), norm += a * a;
    }
  EXPECT_LT(std::sqrt(err / norm), 0.1);
}

// --- MIS weights over all strategies of one path sum to 1 ------------------------------------

/// A surface vertex of the room's Lambert floor material at p with outward normal ng, facing
/// `toward` (where its subpath came from).
BdptVertex surfaceAt(const Scene& s, const Vec3& p, const Vec3& ng, const Vec3& toward) {
  BdptVertex v;
  v.kind = BdptVertex::Kind::kSurface;
  v.p = p, v.ng = ng;
  v.s.p = p, v.s.ng = ng, v.s.n = ng, v.s.front = ng;
  v.m = &s.materials[0];
  v.sm = ShadingMaterial::of(s.materials[0], ng);
  v.n = dot(toward - p, ng) >= 0 ? ng : -ng;
  v.wo = normalize(toward - p);
  v.nonDelta = true;
  return v;
}

/// The subpaths of the path x (positions p, normals ng; x[0] the camera, the last a point on
/// light `light`) cut into a camera prefix of t vertices and a light suffix of s, with the
/// densities the walks would have given them (BdptTracer::walk, lightSubpath, connectS1).
void cut(const Scene& scene, const BdptTracer& tr, const std::vector<Vec3>& p,
         const std::vector<Vec3>& ng, int light, int s, int t, std::vector<BdptVertex>& cam,
         std::vector<BdptVertex>& lit) {
  const int n = int(p.size());
  const auto at = [&](int i) { return size_t(i); };
  cam.assign(at(t), BdptVertex());
  for (int i = 0; i < t; ++i) {
    BdptVertex& z = cam[at(i)];
    if (i == 0) {
      z.kind = BdptVertex::Kind::kCamera, z.p = p[0], z.pdfFwd = 1;
      continue;
    }
    z = surfaceAt(scene, p[at(i)], ng[at(i)], p[at(i - 1)]);
    if (i == n - 1) {  // s = 0: the camera side found the light
      z.light = light;
      z.Le = Color(1.0f);
    }
    z.pdfFwd =
        i == 1
            ? tr.camera().pdfFirst(z.p, z.ng)
            : toArea(tr.pdfDirAt(cam[at(i - 1)], cam[at(i - 1)].wo, directionTo(cam[at(i - 1)], z)),
                     cam[at(i - 1)], z);
  }
  for (int i = 1; i + 2 < t; ++i)  // what scattering at z[i+1] toward z[i+2] set
    cam[at(i)].pdfRev = toArea(
        tr.pdfDirAt(cam[at(i + 1)], directionTo(cam[at(i + 1)], cam[at(i + 2)]), cam[at(i + 1)].wo),
        cam[at(i + 1)], cam[at(i)]);
  lit.assign(at(s), BdptVertex());
  for (int j = 0; j < s; ++j) {
    BdptVertex& y = lit[at(j)];
    const int i = n - 1 - j;  // its index in x
    if (j == 0) {
      y.kind = BdptVertex::Kind::kLight, y.p = p[at(i)], y.ng = ng[at(i)], y.light = light;
      y.pdfFwd = tr.pdfLightOrigin(y, normalize(p[at(i - 1)] - y.p));
      continue;
    }
    y = surfaceAt(scene, p[at(i)], ng[at(i)], p[at(i + 1)]);
    y.pdfFwd =
        j == 1
            ? tr.pdfLightTo(lit[0], y)
            : toArea(tr.pdfDirAt(lit[at(j - 1)], lit[at(j - 1)].wo, directionTo(lit[at(j - 1)], y)),
                     lit[at(j - 1)], y);
  }
  for (int j = 0; j + 2 < s; ++j)
    lit[at(j)].pdfRev = toArea(
        tr.pdfDirAt(lit[at(j + 1)], directionTo(lit[at(j + 1)], lit[at(j + 2)]), lit[at(j + 1)].wo),
        lit[at(j + 1)], lit[at(j)]);
}

TEST(Bdpt, MisWeightsOfAPathSumToOne) {
  // Random paths camera -> floor/wall points -> a point on the area light; every way of
  // cutting it into a camera prefix of t >= 1 vertices and a light suffix of s vertices (the
  // light's end either hit by the camera side, s = 0, or a light vertex) gets its weight from
  // the densities the subpaths would carry; they sum to 1 ((1, 1) is not a strategy).
  const Scene scene = room(LightKind::kArea);
  const PreparedScene prepared(scene, scene.cameras.at(0), {32, 32});
  RenderSettings rs = settings("bdpt", 1, 8);
  rs.declare(bdptOptions());
  const BdptTracer tracer(prepared.context(rs));
  const LightSet& lights = tracer.lightSet();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 5;  // vertices: camera, n - 2 surface points, the light point
    std::vector<Vec3> p(static_cast<size_t>(n)), ng(static_cast<size_t>(n));
    p[0] = {0.3f, 1.6f, 4.5f};
    for (int i = 1; i < n - 1; ++i) {
      if (u(rng) < 0.5f)
        p[size_t(i)] = {6 * u(rng) - 3, 0, 2 * u(rng) - 1}, ng[size_t(i)] = {0, 1, 0};
      else
        p[size_t(i)] = {6 * u(rng) - 3, 3 * u(rng), -2}, ng[size_t(i)] = {0, 0, 1};
    }
    // A point on the light's first triangle (quadMesh's (0, 1, 2), placed by the node).
    const float a = u(rng), b = u(rng) * (1 - a);
    const Vec3 q0{-0.7f, 2.5f, 0.7f}, q1{-0.7f, 2.5f, -0.7f}, q2{0.7f, 2.5f, -0.7f};
    p[size_t(n - 1)] = q0 + a * (q1 - q0) + b * (q2 - q0);
    ng[size_t(n - 1)] = {0, -1, 0};
    // The first interior point must be in view for the camera's density.
    p[1] = {2 * u(rng) - 1, 0, 2 * u(rng) - 1}, ng[1] = {0, 1, 0};
    double sum = 0;
    for (int t = 1; t <= n; ++t) {
      const int s = n - t;
      if (s == 1 && t == 1) continue;
      std::vector<BdptVertex> cam, lit;
      cut(scene, tracer, p, ng, lights.lightAt(3, 0), s, t, cam, lit);
      sum += tracer.weight(lit, cam, s, t);
    }
    EXPECT_NEAR(sum, 1.0, 1e-4) << "path of " << n << " vertices, trial " << trial;
  }
}

// --- Determinism, regions, refusals ---------------------------------------------------------

TEST(Bdpt, BitIdenticalForAnyThreadCount) {
  const Scene s = room(LightKind::kSpot);
  Job job;
  job.integrator = "bdpt", job.spp = 4, job.size = 24, job.threads = 1;
  const Render one = render(s, job);
  job.threads = 4;
  const Render four = render(s, job);
  EXPECT_EQ(differingValues(one.film, four.film), 0u);
}

TEST(Bdpt, RegionsEqualTheWholeImagesPixels) {
  const Scene s = room(LightKind::kArea);
  Job job;
  job.integrator = "bdpt", job.spp = 4, job.size = 24, job.threads = 2;
  const Render whole = render(s, job);
  job.x0 = 5, job.y0 = 9, job.width = 13, job.height = 7;
  const Render part = render(s, job);
  size_t differ = 0;
  for (int y = 0; y < job.height; ++y)
    for (int x = 0; x < job.width; ++x)
      for (int c = 0; c < 4; ++c)
        differ += part.film.pixel(Film::kBeauty, x, y)[c] !=
                  whole.film.pixel(Film::kBeauty, x + job.x0, y + job.y0)[c];
  EXPECT_EQ(differ, 0u);
}

TEST(Bdpt, RefusesWhatItCannotDoInOneLine) {
  const Scene s = room(LightKind::kArea);
  Job job;
  job.integrator = "bdpt", job.spp = 4, job.size = 8;
  job.samples = SampleRange{0, 2};
  EXPECT_THROW(render(s, job), Error);  // the frame renderer's --sample-range refusal
  // Adaptive sampling and time limits: every pixel takes --spp samples.
  RenderSettings adaptive = settings("bdpt", 16, 4);
  adaptive.set("noise-threshold", 0.05f);
  EXPECT_NE(errorOf([&] { renderOf(s, adaptive, 8); }).find("--noise-threshold"),
            std::string::npos);
  // The light-path AOVs (the frame renderer's refusal).
  try {
    renderFilm(s, s.cameras.at(0), 8, 8, settings("bdpt", 1, 4), nullptr, {"diffuse_direct"});
    ADD_FAILURE() << "--aov lightpaths was not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("light-path"), std::string::npos) << e.what();
  }
  // As adaptive's inner integrator: it cannot trace single camera rays.
  RenderSettings wrapped = settings("adaptive", 1, 4);
  wrapped.set("inner", "bdpt");
  EXPECT_NE(errorOf([&] { renderOf(s, wrapped, 8); }).find("single camera rays"),
            std::string::npos);
  Scene lens = room(LightKind::kArea);
  lens.cameras[0].lensRadius = 0.1f, lens.cameras[0].focusDistance = 4;
  try {
    renderOf(lens, settings("bdpt", 1, 4), 8);
    ADD_FAILURE() << "a thin lens was not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("thin lens"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tray

// Stochastic progressive photon mapping (integrators/sppm.h, docs/sppm.md): closed forms (an
// emitting, reflecting closed box at each --max-depth; a glass sphere's caustic carrying the
// flux the sphere intercepts), the Cornell box against Mitsuba's converged mean, every light
// kind against the path tracer, and the determinism the frame hook promises: any thread count,
// and regions that stitch bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "bench/sky_maps.h"
#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "materials/fresnel.h"
#include "render/prepared_scene.h"
#include "tests/error_of.h"
#include "tests/light_scenes.h"
#include "tests/render_film.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

struct Rendered {
  Film film{1, 1};
  RenderStats stats;
};

/// Renders `scene` (its first camera) at w x h with `settings` (integrator, spp, ...), `options`
/// choosing the region, threads and AOVs; the film is the region's when options' film size is
/// given as (rw, rh) > 0.
Rendered renderWith(const Scene& scene, int w, int h, const RenderSettings& settings,
                    RenderOptions options = {}, int rw = 0, int rh = 0) {
  const PreparedScene prepared(scene, scene.cameras.at(0), {w, h}, "embree");
  auto integrator = prepared.integrator(settings);
  Rendered r;
  r.film = rw > 0 ? Film(rw, rh) : Film(w, h);
  RenderState state;
  r.stats = renderImage(*integrator, r.film, state, options);
  return r;
}

RenderSettings sppm(int iterations, int photons, int maxDepth = 8) {
  RenderSettings s;
  s.set("integrator", "sppm");
  s.set("spp", iterations);
  s.set("photons", photons);
  s.set("max-depth", maxDepth);
  return s;
}

Color mean(const Film& f) { return meanBeauty(f); }

/// The inside of a closed box [-1, 1]^3 whose faces all emit Le (both sides) and reflect
/// albedo a (Lambert), the camera at its centre.
Scene emittingBox(float a, float Le) {
  Scene s;
  Material m = diffuse(Color(a));
  m.emissive = Color(Le);
  m.doubleSided = true;
  const int mat = addMaterial(s, m);
  TriangleMesh box;
  box.positions = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  box.indices = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                 3, 2, 6, 3, 6, 7, 0, 3, 7, 0, 7, 4, 1, 5, 6, 1, 6, 2};
  box.material = mat;
  addMeshInstance(s, addMesh(s, std::move(box)), Mat4::identity());
  s.cameras.push_back(lookAt({0, 0, 0}, {0.3f, 0.2f, 1}, 1.2f));
  s.finalize();
  return s;
}

// Every point of the box sees radiance Le sum_{j < D} a^j with paths of at most D segments:
// depth 1 the emission seen, 2 adds the direct light (next-event estimation at the visible
// points, exact here), 3 and more the photons gathered after their first bounce.
TEST(Sppm, EmittingBoxMatchesTheClosedFormAtEachDepth) {
  const float a = 0.8f, Le = 0.5f;
  const Scene s = emittingBox(a, Le);
  for (int depth : {1, 2, 3, 8}) {
    const float expected = Le * (1 - std::pow(a, float(depth))) / (1 - a);
    // Depth 2: 24 passes, its NEE's noise (about 0.5% at 6) below the tolerance for any seed
    // or light sampling (issue 37's rectangles moved one 6-pass estimate to -0.8%).
    const Color m = mean(renderWith(s, 24, 24, sppm(depth == 2 ? 24 : 6, 40000, depth)).film);
    // NEE alone (depth <= 2) is exact up to its noise; photons carry (1 - a^D) / (1 - a) - 1 - a
    // of it at depth D (59% at D = 8), with the density estimate's bias at the box's edges.
    const float tolerance = depth <= 2 ? 0.005f : 0.02f;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], expected, tolerance * expected) << depth;
  }
}

// Mitsuba 3's converged render of the Cornell box has channel means R 0.24015, G 0.14113,
// B 0.05998 (/work/shared/reference/README.md). 24 iterations of 60000 photons at 48 x 48.
TEST(Sppm, CornellBoxMeanMatchesTheReference) {
  const Scene s = loadGltf(std::string(TRAY_SHARED_DIR) + "/reference/cornell-box.gltf");
  const Color m = mean(renderWith(s, 48, 48, sppm(24, 60000)).film);
  const Color ref(0.24015f, 0.14113f, 0.05998f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], ref[c], 0.015f * ref[c]) << c;
}

/// A floor of albedo 0.5 at y = 0, a smooth glass sphere (ior 1.5) of radius R at height 1 and
/// a spot light at height H straight above it whose inner cone holds the whole sphere.
constexpr float kR = 0.5f, kH = 6.0f, kSpot = 50.0f;
Scene causticScene() {
  Scene s;
  addMeshInstance(s, addMesh(s, quadMesh(4, addMaterial(s, diffuse(Color(0.5f))))),
                  Mat4::identity());
  Material glass;
  glass.baseColor = Color(1.0f);
  glass.metallic = 0, glass.roughness = 0, glass.transmission = 1, glass.ior = 1.5f;
  addSphere(s, {0, 1, 0}, kR, addMaterial(s, glass));
  s.lights.push_back(spotLight({0, kH, 0}, {0, -1, 0}, Color(kSpot), 0.12f, 0.14f));
  s.cameras.push_back(lookAt({0, 2.2f, 3.2f}, {0, 0, 0}, 0.5f));
  s.finalize();
  return s;
}

/// Whether the segment from floor point p to the light passes through the sphere (its shadow).
bool inShadow(const Vec3& p) {
  const Vec3 light(0, kH, 0), c(0, 1, 0);
  const Vec3 d = normalize(light - p);
  const float b = dot(c - p, d);
  const Vec3 closest = p + b * d - c;
  return b > 0 && dot(closest, closest) < kR * kR;
}

/// The flux reaching the floor in the sphere's shadow, from the floor's radiance (irradiance
/// E = pi L / albedo): each pixel whose centre sees the floor in the shadow (not the sphere)
/// counts with the floor area its four corners span.
double shadowFlux(const Film& film, const CameraDesc& desc) {
  const auto camera = Camera::create(desc, film.width(), film.height());
  auto onFloor = [&](float rx, float ry, Vec3& p) {
    const Ray r = camera->generateRay(rx, ry);
    if (!(r.d.y < 0)) return false;
    p = r.o + r.d * (-r.o.y / r.d.y);
    return true;
  };
  double flux = 0;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      Vec3 centre, q[4];
      if (!onFloor(x + 0.5f, y + 0.5f, centre) || !inShadow(centre)) continue;
      const Ray r = camera->generateRay(x + 0.5f, y + 0.5f);  // the sphere hides this pixel?
      const Vec3 oc = r.o - Vec3(0, 1, 0);
      const float b = dot(oc, normalize(r.d)), cc = dot(oc, oc) - kR * kR;
      if (b * b - cc > 0) continue;
      for (int k = 0; k < 4; ++k) onFloor(float(x + (k & 1)), float(y + (k >> 1)), q[k]);
      const double area = 0.5 * length(cross(q[3] - q[0], q[2] - q[1]));
      flux += kPi * film.pixel(Film::kBeauty, x, y)[1] / 0.5 * area;
    }
  return flux;
}

/// Ray optics of the spot's light through the sphere, over a 600 x 600 grid of directions in
/// the cone the sphere subtends (equal solid angles: the spot's intensity is constant there),
/// as fractions of the flux the sphere intercepts: `direct`, what leaves after two refractions
/// and lands in the shadow, weighted (1 - F_in)(1 - F_out) (unpolarised Fresnel, as the BSDF's);
/// `reflected`, what is reflected inside at least once, wherever it goes: sum over k >= 1 of
/// (1 - F)^2 F^k = (1 - F) F, the internal angle being the same at every bounce in a sphere.
struct SphereOptics {
  double direct = 0, reflected = 0;
};
SphereOptics sphereOptics() {
  const Vec3 light(0, kH, 0), c(0, 1, 0);
  const double d = kH - 1, cosMax = std::sqrt(1 - kR * kR / (d * d));
  const int n = 600;
  SphereOptics o;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const float ct = float(1 - (i + 0.5) / n * (1 - cosMax)), st = std::sqrt(1 - ct * ct);
      const float phi = 2 * kPi * float(j + 0.5) / n;
      const Vec3 w(st * std::cos(phi), -ct, st * std::sin(phi));
      // Entering: the near intersection of the ray from the light with the sphere.
      const Vec3 oc = light - c;
      const float b = dot(oc, w), disc = b * b - (dot(oc, oc) - kR * kR);
      if (!(disc > 0)) continue;
      const Vec3 p1 = light + (-b - std::sqrt(disc)) * w, n1 = (p1 - c) / kR;
      const float fIn = fresnelDielectric(dot(-w, n1), 1.5f);
      float eta;
      Vec3 t1, t2;
      refractDirection(-w, n1, 1.5f, eta, t1);
      // Leaving: the far intersection along t1, through the normal facing inside.
      const Vec3 p2 = p1 + (-2 * dot(p1 - c, t1)) * t1, n2 = (p2 - c) / kR;
      const float fOut = fresnelDielectric(dot(-t1, n2), 1.5f);
      o.reflected += (1 - fIn) * fOut;
      if (!refractDirection(-t1, n2, 1.5f, eta, t2) || !(t2.y < 0)) continue;
      if (inShadow(p2 + (-p2.y / t2.y) * t2)) o.direct += (1 - fIn) * (1 - fOut);
    }
  o.direct /= double(n) * n;
  o.reflected /= double(n) * n;
  return o;
}

// The sphere intercepts the flux I Omega, Omega = 2 pi (1 - sqrt(1 - R^2 / d^2)) its solid
// angle from the spot (inside the inner cone: intensity I). In the shadow the floor gets no
// direct light: what SPPM finds there is the refracted light of sphereOptics (between its
// direct part and that plus every internal reflection), and the little that path tracing also
// finds (the lit floor's light refracted down by the sphere). Path tracing cannot find a point
// light through glass: only that little.
TEST(Sppm, CausticCarriesTheFluxRayOpticsPredicts) {
  const Scene s = causticScene();
  const double d = kH - 1;
  const double intercepted = kSpot * 2 * kPi * (1 - std::sqrt(1 - kR * kR / (d * d)));
  const SphereOptics optics = sphereOptics();
  RenderSettings path;
  path.set("integrator", "path");
  path.set("spp", 16);
  const double traced = shadowFlux(renderWith(s, 64, 48, path).film, s.cameras[0]);
  const double caustic = shadowFlux(renderWith(s, 64, 48, sppm(8, 100000)).film, s.cameras[0]);
  const double lo = optics.direct * intercepted + traced;
  const double hi = (optics.direct + optics.reflected) * intercepted + traced;
  EXPECT_GT(caustic, 0.98 * lo);
  EXPECT_LT(caustic, 1.02 * hi);
  EXPECT_LT(traced, 0.03 * caustic);
  std::printf("caustic flux %.4f, ray optics %.4f .. %.4f, path %.4f (intercepted %.4f)\n", caustic,
              lo, hi, traced, intercepted);
}

// Photons from every light kind: emissive triangles, emissive spheres, point and spot lights
// (manyLightsScene); a directional sun and a constant sky (sunAndSkyScene); an image sky. The
// image means agree with the path tracer's within 2%.
TEST(Sppm, EveryLightKindAgreesWithThePathTracer) {
  std::vector<Scene> scenes;
  scenes.push_back(manyLightsScene());
  scenes.push_back(sunAndSkyScene());
  scenes.push_back(sunAndSkyScene());
  scenes.back().lights.clear();
  scenes.back().environment.map = maps::sunSky(64, 32);
  scenes.back().finalize();
  for (const Scene& s : scenes) {
    RenderSettings path;
    path.set("integrator", "path");
    path.set("spp", 256);
    const Color expected = mean(renderWith(s, 32, 32, path).film);
    const Color m = mean(renderWith(s, 32, 32, sppm(20, 30000)).film);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], expected[c], 0.02f * expected[c]) << c;
  }
}

Film renderCornell(int threads, int x0 = 0, int y0 = 0, int w = 0, int h = 0) {
  static const Scene s = loadGltf(std::string(TRAY_SHARED_DIR) + "/reference/cornell-box.gltf");
  RenderOptions options;
  options.threads = threads;
  options.x0 = x0, options.y0 = y0;
  options.aovs = {"depth", "normal", "albedo", "crypto_object"};
  return renderWith(s, 32, 32, sppm(3, 20000), options, w, h).film;
}

bool sameValues(const Film& a, const Film& b, int dx = 0, int dy = 0) {
  for (size_t l = 0; l < b.layers().size(); ++l)
    for (int y = 0; y < b.height(); ++y)
      for (int x = 0; x < b.width(); ++x)
        for (size_t c = 0; c < b.layers()[l].channels.size(); ++c)
          if (a.pixel(int(l), x + dx, y + dy)[c] != b.pixel(int(l), x, y)[c]) return false;
  return true;
}

TEST(Sppm, SamePixelsForAnyThreadCount) {
  const Film one = renderCornell(1), two = renderCornell(2), five = renderCornell(5);
  EXPECT_TRUE(sameValues(one, two));
  EXPECT_TRUE(sameValues(one, five));
  EXPECT_GT(mean(one).x, 0.1f);
}

// tray-farm bands: every region traces all of each iteration's photons and keeps what its own
// visible points gather, so the bands are the whole image's pixels, bit for bit.
TEST(Sppm, RegionsStitchBitForBit) {
  const Film whole = renderCornell(2);
  const Film top = renderCornell(2, 0, 0, 32, 13), bottom = renderCornell(2, 0, 13, 32, 19);
  const Film inner = renderCornell(2, 7, 5, 11, 9);
  EXPECT_TRUE(sameValues(whole, top));
  EXPECT_TRUE(sameValues(whole, bottom, 0, 13));
  EXPECT_TRUE(sameValues(whole, inner, 7, 5));
}

TEST(Sppm, TimeLimitEndsAfterAWholeIteration) {
  const Scene s = emittingBox(0.5f, 1.0f);
  RenderOptions options;
  SamplingPasses passes;
  passes.timeLimit = 1e-9;
  options.passes = passes;
  const Rendered r = renderWith(s, 16, 16, sppm(50, 1000), options);
  EXPECT_EQ(r.stats.passes, 1);
  EXPECT_TRUE(r.stats.timeLimitReached);
  EXPECT_FALSE(r.stats.interrupted);
  EXPECT_NEAR(mean(r.film).x, 1.0f / (1 - 0.5f) * (1 - std::pow(0.5f, 8.0f)), 0.2f);
}

TEST(Sppm, RefusesWhatItCannotDo) {
  const Scene s = emittingBox(0.5f, 1.0f);
  RenderOptions ranged;
  ranged.samples = SampleRange{0, 2};
  EXPECT_NE(errorOf([&] { renderWith(s, 8, 8, sppm(4, 100), ranged); }).find("--sample-range"),
            std::string::npos);
  RenderOptions noise;
  SamplingPasses passes;
  passes.threshold = 0.05f;
  noise.passes = passes;
  EXPECT_NE(errorOf([&] { renderWith(s, 8, 8, sppm(4, 100), noise); }).find("--noise-threshold"),
            std::string::npos);
  RenderSettings wrapped = sppm(4, 100);
  wrapped.set("integrator", "adaptive");
  wrapped.set("inner", "sppm");
  EXPECT_NE(errorOf([&] { renderWith(s, 8, 8, wrapped); }).find("sppm"), std::string::npos);
}

}  // namespace
}  // namespace tray

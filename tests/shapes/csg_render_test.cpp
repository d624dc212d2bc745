// Image-level tests of shapes/csg.cpp: CSG scenes rendered with the Whitted integrator against
// an analytic lens, and against the equivalent triangle meshes. (Ray-level tests: csg_test.cpp.)
#include <gtest/gtest.h>

#include "accel/registry.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "shapes/csg.h"
#include "shapes/mesh_solid.h"
#include "tests/double_vec3.h"
#include "tests/scene_builder.h"
#include "tests/shapes/solid_meshes.h"

namespace tray {
namespace {

using namespace tray::test;

CsgChild child(std::shared_ptr<const Shape> s, const Mat4& m = Mat4::identity(),
               int material = -1) {
  return {std::move(s), Transform(m), material, "child"};
}

Film render(const Scene& scene, const CameraDesc& cam, int w, int h) {
  const PreparedScene prepared(scene, cam, {w, h});  // Whitted, 1 spp, centre
  const RenderContext ctx = prepared.context(RenderSettings{});
  auto integrator = makeIntegrator(ctx);
  Film film(w, h);
  renderImage(*integrator, film, RenderOptions{});
  return film;
}

Color pixel(const Film& f, int x, int y) {
  const float* p = f.pixel(Film::kBeauty, x, y);
  return {p[0], p[1], p[2]};
}

// --- A biconvex lens: intersection of two spheres ------------------------------------------

/// Double-precision vector for the independent reference.
using D3 = DVec3;

/// Both roots of |o + t d - c| = 1 (d unit); false if the line misses.
bool sphereRoots(D3 o, D3 d, D3 c, double& t0, double& t1) {
  D3 oc = o - c;
  double b = dot(oc, d), disc = b * b - (dot(oc, oc) - 1.0);
  if (disc <= 0) return false;
  t0 = -b - std::sqrt(disc), t1 = -b + std::sqrt(disc);
  return true;
}

/// Snell refraction of unit d through unit n facing against d; false on total reflection.
bool refractD(D3 d, D3 n, double eta, D3& out) {
  double cosi = -dot(d, n), sin2t = eta * eta * (1 - cosi * cosi);
  if (sin2t >= 1) return false;
  out = eta * d + (eta * cosi - std::sqrt(1 - sin2t)) * n;
  return true;
}

constexpr double kIor = 1.5, kWallZ = -5, kAlbedo = 0.8, kIntensity = 20;
const D3 kCentreA{0, 0, -0.6}, kCentreB{0, 0, 0.6}, kLight{0.5, 0.3, -3};

/// Radiance along a camera ray through the lens {|p - A| <= 1} n {|p - B| <= 1} onto a lit
/// diffuse wall at z = -5; false where the answer is ambiguous (rim, total reflection).
bool traceLens(D3 o, D3 d, double& radiance) {
  d = unit(d);
  double a0, a1, b0, b1;
  if (sphereRoots(o, d, kCentreA, a0, a1) && sphereRoots(o, d, kCentreB, b0, b1) &&
      std::max(a0, b0) < std::min(a1, b1)) {
    if (std::fabs(a0 - b0) < 1e-2 || std::fabs(a1 - b1) < 1e-2) return false;  // the rim
    D3 p = o + std::max(a0, b0) * d, inside, out;
    D3 n = unit(p - (a0 > b0 ? kCentreA : kCentreB));
    if (!refractD(d, n, 1 / kIor, inside)) return false;
    sphereRoots(p, inside, kCentreA, a0, a1);
    sphereRoots(p, inside, kCentreB, b0, b1);
    if (std::fabs(a1 - b1) < 1e-2) return false;
    D3 q = p + std::min(a1, b1) * inside;
    D3 m = unit(q - (a1 < b1 ? kCentreA : kCentreB));
    if (!refractD(inside, -1.0 * m, kIor, out)) return false;
    o = q, d = out;
  }
  if (d.z >= 0) return false;
  D3 w = o + ((kWallZ - o.z) / d.z) * d, toLight = kLight - w;
  double dist2 = dot(toLight, toLight), cosI = toLight.z / std::sqrt(dist2);
  radiance = kAlbedo / M_PI * kIntensity / dist2 * cosI;
  return true;
}

TEST(CsgRender, LensRefractsAsTheAnalyticLens) {
  Scene s;
  Material glass = diffuse(Color(0.0f));
  glass.phong.transmittance = 1.0f;
  glass.ior = float(kIor);
  int g = addMaterial(s, glass), wall = addMaterial(s, diffuse(Color(float(kAlbedo))));
  addShape(s,
           std::make_shared<Csg>(
               CsgOp::kIntersection,
               std::vector<CsgChild>{
                   child(std::make_shared<Sphere>(1.0f), Mat4::translate({0, 0, -0.6f})),
                   child(std::make_shared<Sphere>(1.0f), Mat4::translate({0, 0, 0.6f}))}),
           Mat4::identity(), g);
  addShape(s, std::make_shared<Box>(Vec3(-40, -40, -6), Vec3(40, 40, float(kWallZ))),
           Mat4::identity(), wall);
  s.lights.push_back(pointLight({0.5f, 0.3f, -3}, Color(float(kIntensity))));
  s.finalize();
  const int W = 48, H = 48;
  CameraDesc cam = lookAt({0, 0, 4}, {0, 0, 0}, 0.5f);
  Film film = render(s, cam, W, H);
  auto camera = Camera::create(cam, W, H);
  int throughLens = 0, checked = 0;
  for (int y = 1; y < H; y += 2)
    for (int x = 1; x < W; x += 2) {
      Ray r = camera->generateRay(x + 0.5f, y + 0.5f);
      double expected;
      if (!traceLens({r.o.x, r.o.y, r.o.z}, {r.d.x, r.d.y, r.d.z}, expected)) continue;
      EXPECT_NEAR(pixel(film, x, y).x, expected, 1e-3 * expected + 1e-6) << x << "," << y;
      ++checked;
      Hit h;
      throughLens += Csg(CsgOp::kIntersection,
                         {child(std::make_shared<Sphere>(1.0f), Mat4::translate({0, 0, -0.6f})),
                          child(std::make_shared<Sphere>(1.0f), Mat4::translate({0, 0, 0.6f}))})
                         .intersect(r, h);
    }
  EXPECT_GT(throughLens, 60);
  EXPECT_GT(checked, 300);
}

// --- CSG of boxes against the equivalent triangle mesh -------------------------------------

/// The L-shaped cross-section left when the quadrant x, y > 0 is cut from [-1, 1]^2 (CCW).
std::vector<Vec2> lShape(float s) {
  return {{-s, -s}, {s, -s}, {s, 0}, {0, 0}, {0, s}, {-s, s}};
}

/// A floor and a light around an object (CSG or mesh) placed by `place`.
struct Stage {
  Scene scene;
  Mat4 place =
      Mat4::translate({0, 1.2f, 0}) * Mat4::rotate(0, 0.25881905f, 0, 0.96592583f);  // 30 deg
  CameraDesc cam = lookAt({3.5f, 3, 5}, {0, 0.8f, 0}, 0.7f);
  int gray, red, green;
  Stage() {
    gray = addMaterial(scene, diffuse(Color(0.7f)));
    red = addMaterial(scene, diffuse(Color(0.8f, 0.2f, 0.1f)));
    green = addMaterial(scene, diffuse(Color(0.1f, 0.7f, 0.2f)));
    addShape(scene, std::make_shared<Plane>(), Mat4::identity(), gray);
    scene.lights.push_back(pointLight({3, 5, 4}, Color(60.0f)));
  }
  Film render() {
    scene.finalize();
    return tray::render(scene, cam, 96, 72);
  }
};

double rmse(const Film& a, const Film& b) {
  const auto &x = a.layers()[0].data, &y = b.layers()[0].data;
  double sum = 0;
  for (size_t i = 0; i < x.size(); ++i) sum += double(x[i] - y[i]) * (x[i] - y[i]);
  return std::sqrt(sum / double(x.size()));
}

/// Pixels whose colour differs visibly (more than 0.02 in a channel).
int differingPixels(const Film& a, const Film& b) {
  int n = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      Color d = abs(pixel(a, x, y) - pixel(b, x, y));
      n += maxComponent(d) > 0.02f;
    }
  return n;
}

enum class Variant { kDifference, kUnion, kMeshChild };

std::shared_ptr<Csg> lPrismCsg(Variant v) {
  auto box = [](Vec3 lo, Vec3 hi) { return std::make_shared<Box>(lo, hi); };
  switch (v) {
    case Variant::kDifference:  // [-1,1]^3 minus a box through the +x+y quadrant
      return std::make_shared<Csg>(
          CsgOp::kDifference,
          std::vector<CsgChild>{
              child(box(Vec3(-1), Vec3(1))),
              child(box(Vec3(-1), Vec3(1)), Mat4::translate({1, 1, 0}) * Mat4::scale({1, 1, 2}))});
    case Variant::kUnion:  // two slabs overlapping in the -x-y quadrant, sharing outer faces
      return std::make_shared<Csg>(CsgOp::kUnion,
                                   std::vector<CsgChild>{child(box({-1, -1, -1}, {1, 0, 1})),
                                                         child(box({-1, -1, -1}, {0, 1, 1}))});
    case Variant::kMeshChild:  // the subtracted box as a closed 12-triangle mesh
      return std::make_shared<Csg>(
          CsgOp::kDifference,
          std::vector<CsgChild>{child(box(Vec3(-1), Vec3(1))),
                                child(std::make_shared<MeshSolid>(boxMesh({0, 0, -2}, {2, 2, 2}),
                                                                  acceleratorFactory("embree")))});
  }
  return nullptr;
}

std::string variantName(Variant v) {
  switch (v) {
    case Variant::kDifference:
      return "BoxMinusBox";
    case Variant::kUnion:
      return "BoxUnionBox";
    case Variant::kMeshChild:
      return "BoxMinusMeshBox";
  }
  return "";
}

class CsgVersusMesh : public ::testing::TestWithParam<Variant> {};

TEST_P(CsgVersusMesh, RendersTheSameImageAsTheEquivalentMesh) {
  Stage csg, mesh;
  addShape(csg.scene, lPrismCsg(GetParam()), csg.place, csg.red);
  addMeshInstance(mesh.scene, addMesh(mesh.scene, prismMesh(lShape(1), -1, 1, mesh.red)),
                  mesh.place);
  Film a = csg.render(), b = mesh.render();
  EXPECT_LT(rmse(a, b), 1e-4);
  EXPECT_EQ(differingPixels(a, b), 0);
  // The object is in view and lit: a good part of the image is the prism.
  int prism = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x)
      prism += pixel(a, x, y).x > 2 * pixel(a, x, y).y && pixel(a, x, y).x > 0.01f;
  EXPECT_GT(prism, 500);
}

INSTANTIATE_TEST_SUITE_P(Variants, CsgVersusMesh,
                         ::testing::Values(Variant::kDifference, Variant::kUnion,
                                           Variant::kMeshChild),
                         [](const auto& info) { return variantName(info.param); });

// --- Coincident faces ----------------------------------------------------------------------

/// [-0.7, 0.7]^3 (red) minus a box (green) flush with three of its faces, each box placed
/// through a different transform so that the shared faces differ by float rounding.
std::shared_ptr<Csg> flushNotch(int red, int green, float tieTolerance) {
  float k = 0.35f / 3.0f;
  return std::make_shared<Csg>(
      CsgOp::kDifference,
      std::vector<CsgChild>{
          child(std::make_shared<Box>(), Mat4::scale(Vec3(0.7f)), red),
          child(std::make_shared<Box>(Vec3(-3), Vec3(3)),
                Mat4::translate({0.35f, 0.35f, 0}) * Mat4::scale({k, k, 0.7f / 3.0f}), green)},
      "notch", tieTolerance);
}

Film flushNotchReference() {
  Stage mesh;
  std::vector<bool> notch = {false, false, true, true, false, false};
  std::vector<bool> outer = {true, true, false, false, true, true};
  addMeshInstance(mesh.scene,
                  addMesh(mesh.scene, prismMesh(lShape(0.7f), -0.7f, 0.7f, mesh.red, outer)),
                  mesh.place);
  addMeshInstance(
      mesh.scene,
      addMesh(mesh.scene, prismMesh(lShape(0.7f), -0.7f, 0.7f, mesh.green, notch, false)),
      mesh.place);
  return mesh.render();
}

TEST(CsgRender, CoincidentFacesHaveNoSpeckle) {
  Film reference = flushNotchReference();
  Stage csg;
  addShape(csg.scene, flushNotch(csg.red, csg.green, Csg::kDefaultTieTolerance), csg.place,
           csg.red);
  EXPECT_EQ(differingPixels(csg.render(), reference), 0);
}

TEST(CsgRender, WithoutTheTieRuleCoincidentFacesSpeckle) {
  // The same scene with exact comparisons: the test above would catch this.
  Film reference = flushNotchReference();
  Stage csg;
  addShape(csg.scene, flushNotch(csg.red, csg.green, 0.0f), csg.place, csg.red);
  EXPECT_GT(differingPixels(csg.render(), reference), 10);
}

}  // namespace
}  // namespace tray

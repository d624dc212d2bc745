// MaterialEvaluator and the pixel footprint: textured factors, normal mapping with computed and
// supplied tangents, and uv derivatives checked against rays through neighbouring pixels.
#include "textures/shading.h"

#include <gtest/gtest.h>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "integrators/registry.h"
#include "lights/light_set.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "shapes/mesh_tangents.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

TextureImage constantImage(const Color& c, int size = 1) {
  TextureImage im;
  im.name = "constant";
  im.width = im.height = size;
  im.pixels.resize(size_t(size) * size * 3);
  for (size_t i = 0; i < im.pixels.size(); i += 3)
    im.pixels[i] = c.x, im.pixels[i + 1] = c.y, im.pixels[i + 2] = c.z;
  return im;
}

/// A quad in the z = 0 plane facing +Z, uv (0, 0) at its top left (-1, 1) like an image.
TriangleMesh imageQuad(int material) {
  TriangleMesh m;
  m.positions = {{-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}};
  m.normals.assign(4, Vec3(0, 0, 1));
  m.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  m.material = material;
  return m;
}

struct QuadHit {
  Hit hit;
  SurfacePoint s;
};

QuadHit hitQuadAtCentre(const Scene& scene) {
  Ray ray{{0.1f, 0.2f, 5}, {0, 0, -1}};
  Hit h;
  h.t = 5;
  h.primitive = 0;
  h.triangle = 0;
  // Barycentrics of (0.1, 0.2) in triangle (v0, v1, v2): solved by hand for this layout.
  // p = v0 + b1 (v1 - v0) + b2 (v2 - v0): x = -1 + 2 b2, y = 1 - 2 b1 - 2 b2.
  h.b2 = (0.1f + 1) / 2;
  h.b1 = (1 - 0.2f) / 2 - h.b2;
  return {h, scene.surface(ray, h)};
}

Scene quadScene(Material m, std::vector<TextureImage> textures) {
  Scene s;
  int mat = addMaterial(s, std::move(m));
  addMeshInstance(s, addMesh(s, imageQuad(mat)), Mat4::identity());
  s.textures = std::move(textures);
  s.finalize();
  return s;
}

TEST(MaterialEvaluator, TexturesMultiplyTheFactors) {
  Material m;
  m.baseColor = {0.5f, 1, 1};
  m.metallic = 0.5f;
  m.roughness = 1.0f;
  m.emissive = Color(2.0f);
  m.baseColorTexture.image = 0;
  m.metallicRoughnessTexture.image = 1;
  m.emissiveTexture.image = 0;
  m.phong = phongFromPbr(m);
  Scene scene =
      quadScene(m, {constantImage({0.2f, 0.4f, 0.6f}), constantImage({0.9f, 0.3f, 0.8f})});
  auto camera = Camera::create(lookAt({0, 0, 5}, {0, 0, 0}), 64, 64);
  MaterialEvaluator eval(scene, *camera, 1);
  QuadHit q = hitQuadAtCentre(scene);
  ShadingMaterial sm = eval.evaluate(q.hit, q.s);
  EXPECT_NEAR(sm.baseColor.x, 0.1f, 1e-6f);
  EXPECT_NEAR(sm.baseColor.y, 0.4f, 1e-6f);
  EXPECT_NEAR(sm.baseColor.z, 0.6f, 1e-6f);
  EXPECT_NEAR(sm.roughness, 0.3f, 1e-6f);  // G
  EXPECT_NEAR(sm.metallic, 0.4f, 1e-6f);   // B x 0.5
  EXPECT_NEAR(sm.emissive.y, 0.8f, 1e-6f);
  // Whitted's Phong follows the textured values: diffuse = base (1 - metallic).
  EXPECT_NEAR(sm.phong.diffuse.z, 0.6f * 0.6f, 1e-6f);
}

/// Shading normal for a constant normal-map texel on the image quad.
Vec3 mappedNormal(const Color& texel, float scale = 1.0f, bool suppliedTangents = false,
                  float sign = 1.0f) {
  Material m;
  m.normalTexture.image = 0;
  m.normalTexture.scale = scale;
  Scene scene = quadScene(m, {constantImage(texel)});
  if (suppliedTangents) {
    scene.meshes[0].tangents.assign(4, Vec3(1, 0, 0));
    scene.meshes[0].tangentSigns.assign(4, sign);
  }
  auto camera = Camera::create(lookAt({0, 0, 5}, {0, 0, 0}), 64, 64);
  MaterialEvaluator eval(scene, *camera, 1);
  QuadHit q = hitQuadAtCentre(scene);
  return eval.evaluate(q.hit, q.s).n;
}

void expectVec(const Vec3& got, const Vec3& want, float tol = 2e-3f) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

TEST(MaterialEvaluator, PathTracerSeesEmissiveTexturesAndDoesNotLightSampleThem) {
  Material m;
  m.baseColor = Color(0.0f);
  m.emissive = Color(2.0f);
  m.emissiveTexture.image = 0;
  Scene scene = quadScene(m, {constantImage({0.25f, 0.5f, 1.0f})});
  EXPECT_EQ(LightSet(scene).triangleCount(), 0u);  // left to BSDF sampling
  RenderSettings settings;
  settings.set("integrator", "path");
  const PreparedScene prepared(scene, lookAt({0, 0, 5}, {0, 0, 0}, 0.3f), {16, 16});
  const RenderContext ctx = prepared.context(settings);
  auto integrator = makeIntegrator(ctx);
  Film film(16, 16);
  renderImage(*integrator, film);
  const float* p = film.pixel(Film::kBeauty, 8, 8);
  EXPECT_FLOAT_EQ(p[0], 0.5f);
  EXPECT_FLOAT_EQ(p[1], 1.0f);
  EXPECT_FLOAT_EQ(p[2], 2.0f);
}

TEST(MaterialEvaluator, NormalMapTiltsTheShadingNormal) {
  // Texel (0.5, 0.5, 1) is the unperturbed normal.
  expectVec(mappedNormal({0.5f, 0.5f, 1.0f}), {0, 0, 1});
  // Red tilts towards +u (image right = +X here), green towards image up (-v = +Y here).
  const float s = 0.5f, c = std::sqrt(0.75f);
  expectVec(mappedNormal({0.5f + s / 2, 0.5f, 0.5f + c / 2}), {s, 0, c});
  expectVec(mappedNormal({0.5f, 0.5f + s / 2, 0.5f + c / 2}), {0, s, c});
  // normalTexture.scale scales x and y before normalising.
  Vec3 scaled = mappedNormal({0.5f + s / 2, 0.5f, 0.5f + c / 2}, 2.0f);
  expectVec(scaled, normalize(Vec3(2 * s, 0, c)));
}

TEST(MaterialEvaluator, SuppliedTangentAndItsSignDecideTheFrame) {
  const float s = 0.5f, c = std::sqrt(0.75f);
  const Color up{0.5f, 0.5f + s / 2, 0.5f + c / 2};
  expectVec(mappedNormal(up, 1.0f, true, 1.0f), {0, s, c});
  expectVec(mappedNormal(up, 1.0f, true, -1.0f), {0, -s, c});  // mirrored bitangent
}

TEST(MeshTangents, FollowUAndDetectMirroredUvs) {
  TriangleMesh m = imageQuad(0);
  computeTangents(m);
  ASSERT_EQ(m.tangents.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    expectVec(m.tangents[i], {1, 0, 0}, 1e-5f);
    EXPECT_EQ(m.tangentSigns[i], 1.0f);
  }
  for (auto& uv : m.uvs) uv.y = 1 - uv.y;  // image flipped vertically: bitangent mirrored
  computeTangents(m);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(m.tangentSigns[i], -1.0f);
}

TEST(PixelFootprint, MatchesRaysThroughNeighbouringPixels) {
  // A tilted plane (uv = world x, z of its object space) seen by a perspective camera: the uv
  // change per pixel predicted at a hit equals that of the rays one pixel right and one down.
  Scene scene;
  int mat = addMaterial(scene, Material{});
  Mat4 tilt = Mat4::rotate(std::sin(0.3f), 0, 0, std::cos(0.3f));  // 0.6 rad about X
  addShape(scene, std::make_shared<Plane>(), Mat4::translate({0, -1, 0}) * tilt, mat);
  scene.finalize();
  const int W = 200, H = 150;
  auto camera = Camera::create(lookAt({0.5f, 1.5f, 4}, {0, -1, 0}, 0.7f), W, H);
  auto hitAt = [&](float x, float y, Hit& h, SurfacePoint& s) {
    Ray r = camera->generateRay(x, y);
    if (!scene.intersectShape(0, r, h)) return false;
    s = scene.surface(r, h);
    return true;
  };
  for (auto [px, py] : {std::pair{100.5f, 75.5f}, {30.5f, 120.5f}, {170.5f, 90.5f}}) {
    Hit h, hx, hy;
    SurfacePoint s, sx, sy;
    ASSERT_TRUE(hitAt(px, py, h, s) && hitAt(px + 1, py, hx, sx) && hitAt(px, py + 1, hy, sy));
    UvFootprint f = pixelFootprint(surfaceUvFrame(scene, h, s, 0), s.p, s.ng, *camera, 1.0f);
    const float tol = 0.03f * std::max(std::hypot(f.dx.x, f.dx.y), std::hypot(f.dy.x, f.dy.y));
    EXPECT_NEAR(f.dx.x, sx.uv.x - s.uv.x, tol);
    EXPECT_NEAR(f.dx.y, sx.uv.y - s.uv.y, tol);
    EXPECT_NEAR(f.dy.x, sy.uv.x - s.uv.x, tol);
    EXPECT_NEAR(f.dy.y, sy.uv.y - s.uv.y, tol);
  }
}

}  // namespace
}  // namespace tray

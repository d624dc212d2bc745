// Alpha cut-outs and stochastic transparency in the accelerators: the any-hit test of
// textures/alpha.h as Embree's filter callbacks and the BVH's triangle loop apply it.
#include <gtest/gtest.h>

#include "accel/registry.h"
#include "tests/scene_builder.h"
#include "textures/alpha.h"

namespace tray {
namespace {

using namespace tray::test;

/// A 2x1 texture: left texel alpha 1, right texel alpha 0 (colour white).
TextureImage splitAlpha() {
  TextureImage t;
  t.name = "split";
  t.width = 2;
  t.height = 1;
  t.pixels.assign(6, 1.0f);
  t.alpha = {1.0f, 0.0f};
  return t;
}

/// The quad of quadMesh(1) with u = (x + 1) / 2, v = (z + 1) / 2.
TriangleMesh uvQuad(int material) {
  TriangleMesh m = quadMesh(1.0f, material);
  for (const Vec3& p : m.positions) m.uvs.push_back({(p.x + 1) / 2, (p.z + 1) / 2});
  return m;
}

/// One mesh quad, placed at y = 0 through a translation (so rays enter an instance).
Scene quadScene(const Material& material, bool texture) {
  Scene s;
  if (texture) s.textures.push_back(splitAlpha());
  uint32_t mesh = addMesh(s, uvQuad(addMaterial(s, material)));
  addMeshInstance(s, mesh, Mat4::translate({0.25f, 0, 0}));
  s.finalize();
  return s;
}

/// Straight-down rays over an n x n grid of [-1, 1]^2 (shifted with the quad).
Ray gridRay(int i, int j, int n) {
  const float x = -1 + (i + 0.5f) * 2 / n, z = -1 + (j + 0.5f) * 2 / n;
  return Ray{{x + 0.25f, 5, z}, {0, -1, 0}};
}

constexpr const char* kAccelerators[] = {"embree", "bvh", "naive"};

TEST(AlphaFilter, MaskSplitTextureLetsExactlyTheRightHalfThrough) {
  Material m;
  m.alphaMode = AlphaMode::kMask;  // cutoff 0.5; alpha 1 -> 0 across the texture's middle
  m.baseColorTexture.image = 0;
  m.baseColorTexture.wrapS = m.baseColorTexture.wrapT = TextureWrap::kClampToEdge;
  const Scene s = quadScene(m, true);
  constexpr int n = 32;
  for (const char* name : kAccelerators) {
    auto accel = makeAccelerator(name, s);
    int hits = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Ray r = gridRay(i, j, n);
        Hit h;
        const bool hit = accel->intersect(r, h);
        EXPECT_EQ(hit, i < n / 2) << name << " " << i << "," << j;
        EXPECT_EQ(accel->occluded(r), hit) << name << " " << i << "," << j;
        hits += hit;
      }
    EXPECT_EQ(hits, n * n / 2) << name;
  }
}

TEST(AlphaFilter, OpaqueModeIgnoresAlpha) {
  Material m;
  m.alpha = 0.0f;
  m.baseColorTexture.image = 0;
  const Scene s = quadScene(m, true);
  for (const char* name : kAccelerators) {
    auto accel = makeAccelerator(name, s);
    Hit h;
    EXPECT_TRUE(accel->intersect(gridRay(28, 3, 32), h)) << name;
  }
}

TEST(AlphaFilter, BlendIsStochasticAndTheSameInEveryAccelerator) {
  Material m;
  m.alphaMode = AlphaMode::kBlend;
  m.alpha = 0.3f;
  const Scene s = quadScene(m, false);
  constexpr int n = 128;
  std::vector<char> reference;
  for (const char* name : kAccelerators) {
    auto accel = makeAccelerator(name, s);
    std::vector<char> hit;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        Ray r = gridRay(i, j, n);
        Hit h;
        hit.push_back(accel->intersect(r, h));
        EXPECT_EQ(accel->occluded(r), bool(hit.back())) << name;
        r.blend = BlendRays::kHit;  // Whitted's rays: every BLEND surface is a hit
        EXPECT_TRUE(accel->intersect(r, h)) << name;
      }
    if (reference.empty()) reference = hit;
    EXPECT_EQ(hit, reference) << name << " differs from " << kAccelerators[0];
    // 16384 Bernoulli(0.3) draws: sigma = 0.0036; 4 sigma.
    double fraction = 0;
    for (char c : hit) fraction += c;
    EXPECT_NEAR(fraction / hit.size(), 0.3, 0.015) << name;
  }
}

TEST(AlphaFilter, VertexAlphaMultipliesFactor) {
  Material m;
  m.alphaMode = AlphaMode::kMask;
  m.alpha = 0.8f;
  Scene s;
  TriangleMesh q = uvQuad(addMaterial(s, m));
  q.colors.assign(4, Color(1.0f));
  q.colorAlphas = {1.0f, 1.0f, 0.5f, 0.5f};  // x = -1: 0.8; x = 1: 0.4, below the cutoff
  addMeshInstance(s, addMesh(s, q), Mat4::translate({0.25f, 0, 0}));
  s.finalize();
  auto accel = makeAccelerator("embree", s);
  Hit h;
  EXPECT_TRUE(accel->intersect(gridRay(0, 5, 32), h));
  EXPECT_FALSE(accel->intersect(gridRay(31, 5, 32), h));
  EXPECT_FLOAT_EQ(vertexAlpha(s.meshes[0], 0, 0, 0), 1.0f);
}

TEST(TextureAlpha, WrapModesAndBilinear) {
  TextureImage t = splitAlpha();
  TextureRef ref;
  ref.image = 0;
  ref.wrapS = TextureWrap::kClampToEdge;
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {0.1f, 0.5f}), 1.0f);
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {0.5f, 0.5f}), 0.5f);
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {0.9f, 0.5f}), 0.0f);
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {7.9f, 0.5f}), 0.0f);  // clamped
  ref.wrapS = TextureWrap::kRepeat;
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {1.25f, 0.5f}), 1.0f);  // = 0.25, the left texel's centre
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {1.1f, 0.5f}), 0.7f);   // 0.3 x the wrapped right texel
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {1.0f, 0.5f}), 0.5f);  // between the right and left texel
  ref.wrapS = TextureWrap::kMirroredRepeat;
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {1.1f, 0.5f}), 0.0f);  // mirrored: = 0.9
  ref.magFilter = TextureFilter::kNearest;
  ref.wrapS = TextureWrap::kClampToEdge;
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {0.45f, 0.5f}), 1.0f);
  t.alpha.clear();  // no alpha channel: opaque
  EXPECT_FLOAT_EQ(textureAlpha(t, ref, {0.9f, 0.5f}), 1.0f);
}

TEST(AlphaHash, UniformAndDependsOnRayAndTriangle) {
  constexpr int n = 20000, bins = 10;
  int count[bins] = {};
  for (int k = 0; k < n; ++k) {
    Ray r{{float(k) * 1e-3f, 1, 2}, {0, -1, float(k % 7)}};
    float u = alphaHash(r, uint32_t(k % 3), uint32_t(k));
    ASSERT_GE(u, 0.0f);
    ASSERT_LT(u, 1.0f);
    ++count[int(u * bins)];
  }
  for (int c : count) EXPECT_NEAR(c, n / bins, 200);  // sigma = 42
  Ray r{{0, 1, 2}, {0, -1, 0}};
  EXPECT_EQ(alphaHash(r, 1, 2), alphaHash(r, 1, 2));
  EXPECT_NE(alphaHash(r, 1, 2), alphaHash(r, 1, 3));
  EXPECT_NE(alphaHash(r, 1, 2), alphaHash(r, 2, 2));
}

}  // namespace
}  // namespace tray

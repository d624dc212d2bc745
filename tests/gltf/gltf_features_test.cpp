// Core glTF fidelity on tiny documents and the shared feature samples: COLOR_0, alphaMode,
// KHR_materials_unlit, and one warning per unsupported feature.
#include "gltf/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "tests/error_of.h"
#include "tests/gltf/tiny_doc.h"

namespace tray {
namespace {

namespace fs = std::filesystem;
using namespace test;  // TinyDoc and its helpers (tests/gltf/tiny_doc.h)

// --- Core glTF fidelity: COLOR_0, alphaMode, KHR_materials_unlit, unsupported features -------

const fs::path kFeatures = fs::path(TRAY_SHARED_DIR) / "gltf-features";

/// Three meshes over the one triangle, each with COLOR_0 as accessor 2, 3 and 4.
TEST(GltfTiny, VertexColorFormats) {
  TinyDoc d = triangleDoc();
  d.vec3({1, 0.5f, 0.25f, 0, 0, 0, 1, 1, 1});  // float RGB
  d.add(std::vector<uint8_t>{255, 0, 51, 255, 0, 0, 0, 0, 0, 0, 0, 128}, 5121, "VEC4", true, 4);
  d.add(std::vector<uint16_t>{65535, 0, 13107, 65535, 0, 0, 0, 0, 0, 0, 0, 32768}, 5123, "VEC4",
        true, 4);
  Scene s = d.load(R"("scenes":[{"nodes":[0,1,2]}],"nodes":[{"mesh":0},{"mesh":1},{"mesh":2}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0,"COLOR_0":2},"indices":1}]},
      {"primitives":[{"attributes":{"POSITION":0,"COLOR_0":3},"indices":1}]},
      {"primitives":[{"attributes":{"POSITION":0,"COLOR_0":4},"indices":1}]}])");
  ASSERT_EQ(s.meshes.size(), 3u);
  ASSERT_EQ(s.meshes[0].colors.size(), 3u);
  EXPECT_TRUE(s.meshes[0].colorAlphas.empty());  // RGB: alpha 1
  expectNear(s.meshes[0].colors[0], {1, 0.5f, 0.25f});
  for (int k : {1, 2}) {  // normalized unsigned byte and short (glTF 2.0 §3.11)
    const TriangleMesh& m = s.meshes[size_t(k)];
    ASSERT_EQ(m.colors.size(), 3u);
    ASSERT_EQ(m.colorAlphas.size(), 3u);
    expectNear(m.colors[0], {1, 0, 0.2f});
    EXPECT_FLOAT_EQ(m.colorAlphas[0], 1.0f);
    EXPECT_FLOAT_EQ(m.colorAlphas[1], 0.0f);
    EXPECT_NEAR(m.colorAlphas[2], 0.5f, 0.003f);
  }
}

TEST(GltfTiny, AlphaModesAndUnlit) {
  Scene s = TinyDoc().load(R"("extensionsUsed":["KHR_materials_unlit"],"materials":[
      {"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.3]}},
      {"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.3]}},
      {"alphaMode":"MASK","alphaCutoff":0.25},
      {"alphaMode":"BLEND","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.3]}},
      {"extensions":{"KHR_materials_unlit":{}}}])");
  ASSERT_EQ(s.materials.size(), 5u);
  EXPECT_EQ(s.materials[0].alphaMode, AlphaMode::kOpaque);
  EXPECT_EQ(s.materials[1].alphaMode, AlphaMode::kMask);
  EXPECT_FLOAT_EQ(s.materials[1].alphaCutoff, 0.5f);
  EXPECT_FLOAT_EQ(s.materials[1].alpha, 0.3f);
  EXPECT_FLOAT_EQ(s.materials[2].alphaCutoff, 0.25f);
  EXPECT_EQ(s.materials[3].alphaMode, AlphaMode::kBlend);
  EXPECT_TRUE(s.materials[4].unlit);
  EXPECT_FALSE(s.materials[3].unlit);
  std::string e = errorOf([] { TinyDoc().load(R"("materials":[{"alphaMode":"CLIP"}])"); });
  EXPECT_NE(e.find("material 0 alphaMode 'CLIP' is not OPAQUE, MASK or BLEND"), std::string::npos)
      << e;
  // Issue 40: 1e40 is finite as a double only; -1 was refused while 1e40 was taken.
  for (const char* cutoff : {"1e40", "-1"}) {
    e = errorOf([&] {
      TinyDoc().load(std::string(R"("materials":[{"alphaMode":"MASK","alphaCutoff":)") + cutoff +
                     "}]");
    });
    EXPECT_NE(e.find("alphaCutoff is negative or not finite"), std::string::npos) << e;
  }
}

TEST(GltfFeatures, SampleAssetsKeepColoursAlphaAndUnlit) {
  Scene vc = loadGltf((kFeatures / "VertexColorTest.glb").string());
  size_t colored = 0;
  for (const auto& m : vc.meshes) colored += !m.colors.empty();
  EXPECT_GT(colored, 0u);
  Scene ab = loadGltf((kFeatures / "AlphaBlendModeTest.glb").string());
  int modes[3] = {0, 0, 0};
  for (const auto& m : ab.materials) ++modes[int(m.alphaMode)];
  EXPECT_GT(modes[int(AlphaMode::kOpaque)], 0);
  EXPECT_GT(modes[int(AlphaMode::kMask)], 0);
  EXPECT_GT(modes[int(AlphaMode::kBlend)], 0);
  bool alphaTexture = false;  // the alpha-tested base colour textures keep their alpha
  for (const auto& m : ab.materials)
    if (m.alphaMode != AlphaMode::kOpaque && m.baseColorTexture.valid())
      alphaTexture = alphaTexture || ab.textures[size_t(m.baseColorTexture.image)].hasAlpha();
  EXPECT_TRUE(alphaTexture);
  Scene unlit = loadGltf((kFeatures / "UnlitTest.glb").string());
  for (const auto& m : unlit.materials) EXPECT_TRUE(m.unlit) << m.name;
}

TEST(GltfFeatures, UnsupportedFeaturesAreWarned) {
  auto warningsOf = [](const char* file) {
    LoadReport report;
    loadGltf((kFeatures / file).string(), {}, &report);
    std::string all;
    for (const auto& w : report.warnings) all += w + "\n";
    return all;
  };
  // Skins, animations and morph targets are read (tests/gltf/gltf_animation_test.cpp): no word.
  EXPECT_EQ(warningsOf("SimpleSkin.gltf"), "");
  EXPECT_EQ(warningsOf("SimpleMorph.gltf"), "");
  std::string sofa = warningsOf("GlamVelvetSofa.glb");
  EXPECT_EQ(sofa.find("KHR_materials_variants"), std::string::npos) << sofa;  // read: --variant
  EXPECT_EQ(sofa.find("sheen"), std::string::npos) << sofa;
  // Implemented layers are no longer warned about.
  std::string clearcoat = warningsOf("ClearCoatTest.glb");
  EXPECT_EQ(clearcoat.find("clearcoat"), std::string::npos) << clearcoat;
  std::string specular = warningsOf("SpecularTest.glb");
  EXPECT_EQ(specular.find("specular"), std::string::npos) << specular;
}

}  // namespace
}  // namespace tray

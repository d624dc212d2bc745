// KHR_materials_variants (--variant): the sofa of the shared samples in each of its five fabrics,
// the names listed for a bad value, and malformed mappings refused with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "core/error.h"
#include "gltf/gltf_loader.h"

namespace tray {
namespace {

namespace fs = std::filesystem;

const std::string kSofa =
    (fs::path(TRAY_SHARED_DIR) / "gltf-features" / "GlamVelvetSofa.glb").string();

/// The material names of the sofa's meshes, in mesh order.
std::vector<std::string> materialsOf(const std::string& variant) {
  LoadOptions options;
  options.variant = variant;
  const Scene scene = loadGltf(kSofa, options);
  std::vector<std::string> names;
  for (const auto& m : scene.meshes) names.push_back(scene.materials[size_t(m.material)].name);
  return names;
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(GltfVariants, NoneKeepsThePrimitivesOwnMaterials) {
  const auto names = materialsOf("none");
  EXPECT_TRUE(has(names, "GlamVelvetSofa_fabric_navy"));  // the file's own choice for the fabric
  EXPECT_TRUE(has(names, "GlamVelvetSofa_legs"));
}

TEST(GltfVariants, ByNameAndByIndexPickTheMappedMaterial) {
  const auto champagne = materialsOf("Champagne");
  EXPECT_TRUE(has(champagne, "GlamVelvetSofa_fabric_champagne"));
  EXPECT_FALSE(has(champagne, "GlamVelvetSofa_fabric_navy"));
  EXPECT_TRUE(has(champagne, "GlamVelvetSofa_legs"));  // no mapping: its own material
  EXPECT_EQ(materialsOf("4"), materialsOf("Pale Pink"));
  EXPECT_TRUE(has(materialsOf("4"), "GlamVelvetSofa_fabric_palepink"));
}

TEST(GltfVariants, ABadValueListsTheVariants) {
  for (const char* bad : {"Purple", "5", "", "-1"}) {
    try {
      materialsOf(bad);
      FAIL() << "--variant '" << bad << "' accepted";
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("GlamVelvetSofa.glb"), std::string::npos) << m;
      EXPECT_NE(m.find("0 'Champagne', 1 'Navy', 2 'Gray', 3 'Black', 4 'Pale Pink'"),
                std::string::npos)
          << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
}

TEST(GltfVariants, AFileWithoutVariantsTakesOnlyNone) {
  const std::string box = (fs::path(TRAY_SHARED_DIR) / "gltf-samples" / "Box.glb").string();
  LoadOptions options;
  EXPECT_NO_THROW(loadGltf(box, options));
  options.variant.assign(1, '0');  // not = "0": GCC 12 warns falsely (-Wrestrict, PR 105329)
  EXPECT_THROW(loadGltf(box, options), Error);
}

/// A one-triangle file whose primitive maps variant `v` to material `m`.
Scene loadMapping(const std::string& mapping, const std::string& variant = "none") {
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) about "literal" + std::string.
  std::string json = R"({"asset":{"version":"2.0"},
    "extensionsUsed":["KHR_materials_variants"],
    "extensions":{"KHR_materials_variants":{"variants":[{"name":"a"},{"name":"b"}]}},
    "materials":[{"name":"m0"},{"name":"m1"}],
    "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0,
      "extensions":{"KHR_materials_variants":{"mappings":[)";
  json += mapping;
  json += R"(]}}}]}],
    "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
  LoadOptions options;
  options.variant = variant;
  return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(json.data()), json.size(),
                            "variants.gltf", options);
}

TEST(GltfVariants, MappingsAreChecked) {
  EXPECT_EQ(loadMapping(R"({"material":1,"variants":[1]})", "b").meshes[0].material, 1);
  EXPECT_EQ(loadMapping(R"({"material":1,"variants":[1]})", "a").meshes[0].material, 0);
  for (const char* bad :
       {R"({"material":2,"variants":[0]})", R"({"material":1,"variants":[2]})", R"({"material":1})",
        R"({"material":-1,"variants":[0]})", R"({"material":1,"variants":[0.5]})"}) {
    try {
      loadMapping(bad);  // checked even when no variant is chosen
      FAIL() << bad << " accepted";
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("variants.gltf: mesh 0 primitive 0 KHR_materials_variants mapping 0"),
                std::string::npos)
          << m;
    }
  }
}

}  // namespace
}  // namespace tray

// Reading KHR_materials_iridescence and KHR_materials_dispersion (gltf/gltf_material_layers.cpp):
// factors, defaults, range errors, and both accepted as required extensions.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "gltf/gltf_loader.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

Scene load(const std::string& rest) {
  static int counter = 0;
  const std::filesystem::path dir = test::testDir() / ("spectral" + std::to_string(counter++));
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "scene.gltf";
  std::ofstream(file) << "{\"asset\":{\"version\":\"2.0\"}," << rest << "}";
  return loadGltf(file.string(), {}, nullptr);
}

TEST(GltfSpectralMaterials, ReadsBothExtensions) {
  const Scene s = load(R"("extensionsUsed":["KHR_materials_iridescence","KHR_materials_dispersion"],
      "extensionsRequired":["KHR_materials_iridescence","KHR_materials_dispersion"],
      "materials":[{"extensions":{
      "KHR_materials_iridescence":{"iridescenceFactor":0.75,"iridescenceIor":1.4,
          "iridescenceThicknessMinimum":50,"iridescenceThicknessMaximum":600},
      "KHR_materials_dispersion":{"dispersion":0.3}}},
      {"extensions":{"KHR_materials_iridescence":{}}}])");
  const MaterialLayers& l = s.materials.at(0).layers;
  EXPECT_FLOAT_EQ(l.iridescence, 0.75f);
  EXPECT_FLOAT_EQ(l.iridescenceIor, 1.4f);
  EXPECT_FLOAT_EQ(l.iridescenceThicknessMin, 50.0f);
  EXPECT_FLOAT_EQ(l.iridescenceThicknessMax, 600.0f);
  EXPECT_FLOAT_EQ(l.dispersion, 0.3f);
  // The untextured thickness is the maximum (the extension's rule).
  EXPECT_FLOAT_EQ(ShadingMaterial::of(s.materials.at(0), Vec3(0, 0, 1)).iridescenceThickness,
                  600.0f);
  // Defaults: factor 0 (off), IOR 1.3, 100-400 nm; no dispersion.
  const MaterialLayers& d = s.materials.at(1).layers;
  EXPECT_EQ(d.iridescence, 0.0f);
  EXPECT_FLOAT_EQ(d.iridescenceIor, 1.3f);
  EXPECT_FLOAT_EQ(d.iridescenceThicknessMin, 100.0f);
  EXPECT_FLOAT_EQ(d.iridescenceThicknessMax, 400.0f);
  EXPECT_EQ(d.dispersion, 0.0f);
}

TEST(GltfSpectralMaterials, RangeErrorsNameTheField) {
  auto error = [](const std::string& ext) {
    return errorOf([&] { load(R"("materials":[{"extensions":{)" + ext + "}}]"); });
  };
  std::string e = error(R"("KHR_materials_iridescence":{"iridescenceFactor":2})");
  EXPECT_NE(e.find("KHR_materials_iridescence 'iridescenceFactor'"), std::string::npos) << e;
  e = error(R"("KHR_materials_iridescence":{"iridescenceThicknessMaximum":-1})");
  EXPECT_NE(e.find("'iridescenceThicknessMaximum'"), std::string::npos) << e;
  e = error(R"("KHR_materials_dispersion":{"dispersion":-0.5})");
  EXPECT_NE(e.find("KHR_materials_dispersion 'dispersion'"), std::string::npos) << e;
}

}  // namespace
}  // namespace tray

// TRAY_materials_scattering (docs/subsurface.md) read from glTF: its fields, its defaults, the
// KHR_materials_volume absorption beside it, and its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "gltf/gltf_loader.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

Scene loadMaterials(const std::string& materials) {
  static int counter = 0;
  const std::filesystem::path dir = test::testDir() / ("sss" + std::to_string(counter++));
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "scene.gltf";
  std::ofstream(file) << R"({"asset":{"version":"2.0"},"materials":[)" << materials << "]}";
  return loadGltf(file.string());
}

const char* kGlass = R"("KHR_materials_transmission":{"transmissionFactor":1},)";

TEST(GltfScattering, ReadsCoefficientAnisotropyAndVolumeAbsorption) {
  const Scene s = loadMaterials(std::string(R"({"extensions":{)") + kGlass +
                                R"("KHR_materials_volume":{"attenuationColor":[0.5,0.5,0.5],
                                   "attenuationDistance":2},
                                   "TRAY_materials_scattering":{"scatteringCoefficient":[1,2,3],
                                   "anisotropy":0.5}}},{})");
  const MaterialLayers& l = s.materials.at(0).layers;
  EXPECT_TRUE(l.scatteringMedium);
  EXPECT_EQ(l.scattering, Color(1, 2, 3));
  EXPECT_FLOAT_EQ(l.scatterAnisotropy, 0.5f);
  EXPECT_NEAR(l.absorption().y, std::log(2.0f) / 2, 1e-6f);
  // Without it: no scattering medium.
  EXPECT_FALSE(s.materials.at(1).layers.scatteringMedium);
  // Defaults: sigma_s 0, isotropic (a medium that only absorbs, through the random walk).
  const Scene d = loadMaterials(std::string(R"({"extensions":{)") + kGlass +
                                R"("TRAY_materials_scattering":{}}})");
  EXPECT_TRUE(d.materials.at(0).layers.scatteringMedium);
  EXPECT_EQ(d.materials.at(0).layers.scattering, Color(0.0f));
  EXPECT_EQ(d.materials.at(0).layers.scatterAnisotropy, 0.0f);
}

TEST(GltfScattering, Errors) {
  const auto error = [](const std::string& ext, bool glass = true) {
    return errorOf([&] {
      loadMaterials(std::string(R"({"extensions":{)") + (glass ? kGlass : "") +
                    R"("TRAY_materials_scattering":)" + ext + "}}");
    });
  };
  std::string e = error(R"({"scatteringCoefficient":[1,1,1]})", false);
  EXPECT_NE(e.find("needs KHR_materials_transmission"), std::string::npos) << e;
  e = error(R"({"anisotropy":1})");
  EXPECT_NE(e.find("'anisotropy'"), std::string::npos) << e;
  e = error(R"({"scatteringCoefficient":[-1,0,0]})");
  EXPECT_NE(e.find("'scatteringCoefficient'"), std::string::npos) << e;
  e = error(R"({"sigmaS":[1,1,1]})");
  EXPECT_NE(e.find("unknown key 'sigmaS'"), std::string::npos) << e;
}

}  // namespace
}  // namespace tray

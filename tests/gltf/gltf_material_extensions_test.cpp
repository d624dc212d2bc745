// KHR_materials_anisotropy and KHR_materials_diffuse_transmission read from glTF: the factors
// and textures land in Material::layers, both are accepted as required extensions, ranges are
// checked with the field named, and the shading point's anisotropy direction follows the
// analytic sphere's tangent (dp/du) rotated by anisotropyRotation.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/camera.h"
#include "gltf/gltf_loader.h"
#include "tests/error_of.h"
#include "tests/scene_builder.h"
#include "textures/shading.h"

namespace tray {
namespace {

// A 1x1 PNG (the loader test's).
const std::string kImage =
    R"("images":[{"uri":"data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGNoaGgAAAMEAYFL09IQAAAAAElFTkSuQmCC"}],
    "textures":[{"source":0}],)";

Scene load(const std::string& materials, const std::string& rest = "") {
  const std::string doc = R"({"asset":{"version":"2.0"},
    "extensionsUsed":["KHR_materials_anisotropy","KHR_materials_diffuse_transmission","TRAY_shape"],
    "extensionsRequired":["KHR_materials_anisotropy","KHR_materials_diffuse_transmission"],)" +
                          kImage + rest + R"("materials":[)" + materials + "]}";
  return loadGltfFromMemory(reinterpret_cast<const unsigned char*>(doc.data()), doc.size(),
                            "extensions.gltf");
}

TEST(GltfMaterialExtensions, FactorsAndTexturesAreRead) {
  const Scene s = load(R"({"extensions":{
      "KHR_materials_anisotropy":{"anisotropyStrength":0.75,"anisotropyRotation":1.25,
                                  "anisotropyTexture":{"index":0,"texCoord":1}},
      "KHR_materials_diffuse_transmission":{"diffuseTransmissionFactor":0.4,
          "diffuseTransmissionColorFactor":[0.5,0.25,1],
          "diffuseTransmissionTexture":{"index":0},
          "diffuseTransmissionColorTexture":{"index":0}}}},{})");
  const MaterialLayers& l = s.materials.at(0).layers;
  EXPECT_FLOAT_EQ(l.anisotropyStrength, 0.75f);
  EXPECT_FLOAT_EQ(l.anisotropyRotation, 1.25f);
  EXPECT_TRUE(l.anisotropyTexture.valid());
  EXPECT_EQ(l.anisotropyTexture.texCoord, 1);
  EXPECT_FLOAT_EQ(l.diffuseTransmission, 0.4f);
  EXPECT_FLOAT_EQ(l.diffuseTransmissionColor.y, 0.25f);
  EXPECT_TRUE(l.diffuseTransmissionTexture.valid() && l.diffuseTransmissionColorTexture.valid());
  EXPECT_TRUE(s.materials.at(0).hasTextures());
  // Without them: the defaults, which change nothing.
  const MaterialLayers& none = s.materials.at(1).layers;
  EXPECT_EQ(none.anisotropyStrength, 0.0f);
  EXPECT_EQ(none.diffuseTransmission, 0.0f);
  EXPECT_FALSE(s.materials.at(1).hasTextures());
}

TEST(GltfMaterialExtensions, RangesNameTheField) {
  std::string e = errorOf(
      [] { load(R"({"extensions":{"KHR_materials_anisotropy":{"anisotropyStrength":1.5}}})"); });
  EXPECT_NE(e.find("KHR_materials_anisotropy 'anisotropyStrength'"), std::string::npos) << e;
  e = errorOf([] {
    load(
        R"({"extensions":{"KHR_materials_diffuse_transmission":{"diffuseTransmissionFactor":-1}}})");
  });
  EXPECT_NE(e.find("KHR_materials_diffuse_transmission 'diffuseTransmissionFactor'"),
            std::string::npos)
      << e;
}

TEST(GltfMaterialExtensions, DirectionFollowsTheTangentRotated) {
  // A TRAY_shape sphere at the origin: dp/du at (0, 0, 1) is along +x (shapes/sphere.cpp), the
  // bitangent n x t along +y; a rotation of pi/2 turns the direction from t to b.
  for (float rotation : {0.0f, 1.5707964f}) {
    const std::string nodes =
        R"("scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"extensions":{"TRAY_shape":
        {"type":"sphere","radius":1,"material":0}}}],)";
    const Scene s = load(R"({"extensions":{"KHR_materials_anisotropy":{"anisotropyStrength":0.5,
                      "anisotropyRotation":)" +
                             std::to_string(rotation) + "}}}",
                         nodes);
    const auto camera = Camera::create(test::lookAt({0, 0, 5}, {0, 0, 0}), 64, 64);
    const MaterialEvaluator materials(s, *camera, 1);
    Hit hit;
    hit.primitive = 0, hit.t = 1, hit.normal = Vec3(0, 0, 1);
    const Ray ray{{0, 0, 2}, {0, 0, -1}};
    const SurfacePoint p = s.surface(ray, hit);
    const ShadingMaterial m = materials.evaluate(hit, p);
    EXPECT_FLOAT_EQ(m.anisotropy, 0.5f);
    const Vec3 d = normalize(m.anisotropyDirection);
    const Vec3 expected = rotation == 0 ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
    EXPECT_GT(std::fabs(dot(d, expected)), 0.999f)
        << rotation << ": " << d.x << " " << d.y << " " << d.z;
  }
}

}  // namespace
}  // namespace tray

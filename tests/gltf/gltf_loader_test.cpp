// loadGltf on every shared sample (counts checked against an independent reading) and on tiny
// glTF documents written to a temporary folder (tests/gltf/tiny_doc.h), one feature each;
// validation and refusals: gltf_loader_validation_test.cpp; colours, alpha, unlit:
// gltf_features_test.cpp.
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



const fs::path kSamples = fs::path(TRAY_SHARED_DIR) / "gltf-samples";

// ---------------------------------------------------------------------------------------------
// Shared samples. Expected numbers come from a separate Python reading of each file (json +
// struct, no tinygltf): walk the default scene's nodes; meshes = triangle-mode primitives
// (modes 4-6) of the distinct glTF meshes used, keeping those with at least one triangle of
// non-zero area (computed in float32); primitives = those times the nodes using each mesh;
// triangles = non-degenerate triangles of the used meshes (strips n-2, fans n-2); lights and
// cameras = nodes carrying one; materials = glTF materials, +1 when a used primitive has none.
// MetalRoughSpheresNoTextures has 196 zero-area triangles, dropped; MeshPrimitiveModes has 4
// point/line primitives, skipped.

struct SampleCounts {
  const char* file;
  size_t meshes, primitives, triangles, lights, cameras, materials;
};

const SampleCounts kSampleCounts[] = {
    {"Avocado/Avocado.gltf", 1, 1, 682, 0, 0, 1},
    {"Box.glb", 1, 1, 12, 0, 0, 1},
    {"BoxTextured.glb", 1, 1, 12, 0, 0, 1},
    {"BoxVertexColors.glb", 1, 1, 12, 0, 0, 1},
    {"Cameras.gltf", 1, 1, 2, 0, 2, 1},
    {"DamagedHelmet.glb", 1, 1, 15452, 0, 0, 1},
    {"Duck.glb", 1, 1, 4212, 0, 1, 1},
    {"EmissiveStrengthTest.glb", 6, 6, 90, 0, 0, 6},
    {"LightsPunctualLamp/LightsPunctualLamp.gltf", 3, 3, 6000, 5, 0, 3},
    {"MeshPrimitiveModes.gltf", 3, 3, 16, 0, 0, 1},
    {"MetalRoughSpheresNoTextures.glb", 123, 123, 1040213, 0, 0, 99},
    {"MultiUVTest.glb", 1, 1, 12, 0, 1, 1},
    {"NegativeScaleTest.glb", 8, 11, 3884, 0, 0, 6},
    {"NormalTangentTest.glb", 1, 1, 7774, 0, 0, 1},
    {"OrientationTest.glb", 13, 13, 524, 0, 0, 7},
    {"SimpleMeshes.gltf", 1, 2, 1, 0, 0, 1},
    {"SimpleSparseAccessor.gltf", 1, 1, 12, 0, 0, 1},
    {"TextureCoordinateTest.glb", 5, 5, 10, 0, 0, 5},
    {"TextureSettingsTest.glb", 10, 10, 72, 0, 0, 10},
    {"TransmissionRoughnessTest.glb", 9, 9, 77792, 0, 0, 9},
    {"TransmissionTest.glb", 22, 22, 128775, 0, 1, 14},
    {"Triangle.gltf", 1, 1, 1, 0, 0, 1},
    {"TriangleWithoutIndices.gltf", 1, 1, 1, 0, 0, 1},
};

class GltfSample : public ::testing::TestWithParam<SampleCounts> {};

TEST_P(GltfSample, CountsMatchIndependentReading) {
  const SampleCounts& c = GetParam();
  Scene s = loadGltf((kSamples / c.file).string());
  size_t triangles = 0;
  for (const auto& m : s.meshes) triangles += m.triangleCount();
  EXPECT_EQ(s.meshes.size(), c.meshes);
  EXPECT_EQ(s.primitives.size(), c.primitives);
  EXPECT_EQ(triangles, c.triangles);
  EXPECT_EQ(s.lights.size(), c.lights);
  EXPECT_EQ(s.cameras.size(), c.cameras);
  EXPECT_EQ(s.materials.size(), c.materials);
}

std::string sampleName(const ::testing::TestParamInfo<SampleCounts>& info) {
  std::string name = fs::path(info.param.file).stem().string();
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Shared, GltfSample, ::testing::ValuesIn(kSampleCounts), sampleName);

TEST(GltfSamples, EverySampleIsCounted) {
  size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(kSamples)) {
    auto ext = e.path().extension();
    bool invalid = e.path().parent_path().filename() == "invalid";
    if (!invalid && (ext == ".gltf" || ext == ".glb")) ++files;
  }
  EXPECT_EQ(files, std::size(kSampleCounts));
}

TEST(GltfSamples, SparseAccessorReplacesValues) {
  // SimpleSparseAccessor.gltf: 14 vertices on y = 0 (x = 0..6) and y = 1; the sparse part
  // moves vertices 8, 10, 12 to y = 2, 3, 4.
  Scene s = loadGltf((kSamples / "SimpleSparseAccessor.gltf").string());
  const auto& p = s.meshes.at(0).positions;
  ASSERT_EQ(p.size(), 14u);
  EXPECT_EQ(p[7].y, 1.0f);
  EXPECT_EQ(p[8].y, 2.0f);
  EXPECT_EQ(p[10].y, 3.0f);
  EXPECT_EQ(p[12].y, 4.0f);
  EXPECT_EQ(p[13].y, 1.0f);
}

TEST(GltfSamples, CamerasInNodeOrder) {
  Scene s = loadGltf((kSamples / "Cameras.gltf").string());
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_EQ(s.cameras[0].type, CameraDesc::Type::kPerspective);
  EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.7f);
  EXPECT_FLOAT_EQ(s.cameras[0].aspectRatio, 1.0f);
  EXPECT_FLOAT_EQ(s.cameras[0].znear, 0.01f);
  EXPECT_EQ(s.cameras[1].type, CameraDesc::Type::kOrthographic);
  EXPECT_FLOAT_EQ(s.cameras[1].xmag, 1.0f);
  Vec3 eye = s.cameras[0].toWorld.point({0, 0, 0});
  EXPECT_FLOAT_EQ(eye.z, 3.0f);
}

TEST(GltfSamples, LampLightIntensityIsColorTimesIntensity) {
  Scene s = loadGltf((kSamples / "LightsPunctualLamp/LightsPunctualLamp.gltf").string());
  ASSERT_EQ(s.lights.size(), 5u);
  EXPECT_NEAR(s.lights[0].intensity.x, 15.0f, 1e-4);
  EXPECT_NEAR(s.lights[0].intensity.y, 15.0f * 0.6318749785423279f, 1e-4);
}

TEST(GltfSamples, PointAndLinePrimitivesGiveOneWarning) {
  LoadReport report;
  loadGltf((kSamples / "MeshPrimitiveModes.gltf").string(), {}, &report);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("skipped 4 point or line"), std::string::npos);
}

TEST(GltfSamples, EmissiveStrengthMultipliesEmission) {
  Scene s = loadGltf((kSamples / "EmissiveStrengthTest.glb").string());
  float brightest = 0;
  for (const auto& m : s.materials) brightest = std::max(brightest, maxComponent(m.emissive));
  EXPECT_GT(brightest, 1.0f);  // strengths above 1 only come from the extension
}

// ---------------------------------------------------------------------------------------------
// Tiny documents, one feature each.


TEST(GltfTiny, TrsEqualsMatrix) {
  // T(1,2,3) * R(90 deg about Y) * S(2,2,2), column-major.
  Scene s = triangleDoc().load(kTriangleMesh + R"(,"scenes":[{"nodes":[0,1]}],"nodes":[
      {"mesh":0,"translation":[1,2,3],"rotation":[0,0.70710678,0,0.70710678],"scale":[2,2,2]},
      {"mesh":0,"matrix":[0,0,-2,0, 0,2,0,0, 2,0,0,0, 1,2,3,1]}])");
  ASSERT_EQ(s.primitives.size(), 2u);
  for (Vec3 p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.3f, -2, 5)})
    expectNear(s.primitives[0].toWorld.point(p), s.primitives[1].toWorld.point(p));
  expectNear(s.primitives[0].toWorld.point({1, 0, 0}), {1, 2, 1});
}

TEST(GltfTiny, HierarchyComposesParentFirst) {
  Scene s = triangleDoc().load(kTriangleMesh + R"(,"scenes":[{"nodes":[0]}],"nodes":[
      {"translation":[10,0,0],"scale":[2,2,2],"children":[1]},
      {"translation":[0,1,0],"children":[2]},
      {"mesh":0,"name":"leaf"}])");
  ASSERT_EQ(s.primitives.size(), 1u);
  EXPECT_EQ(s.primitives[0].objectId, 2);
  EXPECT_EQ(s.primitives[0].name, "leaf");
  // world = T(10,0,0) S(2) T(0,1,0): (1,0,0) -> (12, 2, 0)
  expectNear(s.primitives[0].toWorld.point({1, 0, 0}), {12, 2, 0});
}

TEST(GltfTiny, StripsAndFansTriangulate) {
  TinyDoc d;
  d.vec3({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0});   // zig-zag strip, 5 vertices
  d.vec3({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 0, 0});  // fan around vertex 0
  Scene s = d.load(R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[
      {"attributes":{"POSITION":0},"mode":5},{"attributes":{"POSITION":1},"mode":6}]}])");
  ASSERT_EQ(s.meshes.size(), 2u);
  // glTF 2.0 §3.7.2.1: strip triangles alternate winding to keep facing; fans pivot on 0.
  EXPECT_EQ(s.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
  EXPECT_EQ(s.meshes[1].indices, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
  Vec3 n0 = cross(s.meshes[0].positions[1] - s.meshes[0].positions[0],
                  s.meshes[0].positions[2] - s.meshes[0].positions[0]);
  Vec3 n1 = cross(s.meshes[0].positions[3] - s.meshes[0].positions[1],
                  s.meshes[0].positions[2] - s.meshes[0].positions[1]);
  EXPECT_GT(dot(n0, n1), 0);  // same facing
}

TEST(GltfTiny, NormalizedTexcoords) {
  TinyDoc d = triangleDoc();
  d.add(std::vector<uint8_t>{0, 255, 128, 0, 255, 51}, 5121, "VEC2", true, 2);
  d.add(std::vector<uint16_t>{0, 65535, 32768, 0, 65535, 13107}, 5123, "VEC2", true, 2);
  Scene s = d.load(R"("scenes":[{"nodes":[0,1]}],"nodes":[{"mesh":0},{"mesh":1}],"meshes":[
      {"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":2},"indices":1}]},
      {"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":3},"indices":1}]}])");
  ASSERT_EQ(s.meshes.size(), 2u);
  for (const auto& m : s.meshes) {
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_FLOAT_EQ(m.uvs[0].x, 0.0f);
    EXPECT_FLOAT_EQ(m.uvs[0].y, 1.0f);
    EXPECT_NEAR(m.uvs[1].x, 0.5f, 0.002f);
    EXPECT_NEAR(m.uvs[2].y, 0.2f, 1e-6f);
  }
}

TEST(GltfTiny, NonNormalizedByteTexcoordsAreRefused) {
  TinyDoc d = triangleDoc();
  d.add(std::vector<uint8_t>{0, 1, 1, 0, 1, 1}, 5121, "VEC2", false, 2);
  std::string e = errorOf([&] {
    d.load(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":2}}]}])");
  });
  EXPECT_NE(e.find("accessor 2 (TEXCOORD_0)"), std::string::npos) << e;
}

TEST(GltfTiny, TrayShapes) {
  TinyDoc d;
  Scene s = d.load(R"("extensionsUsed":["TRAY_shape"],"materials":[{"name":"red"}],
      "scenes":[{"nodes":[0,1,2]}],"nodes":[
      {"extensions":{"TRAY_shape":{"type":"sphere","radius":2.5,"material":0}},"translation":[0,3,0]},
      {"extensions":{"TRAY_shape":{"type":"plane"}}},
      {"extensions":{"TRAY_shape":{"type":"box","min":[-1,-2,-3],"max":[1,2,3]}}}])");
  ASSERT_EQ(s.primitives.size(), 3u);
  for (const auto& p : s.primitives) EXPECT_EQ(p.kind, Primitive::Kind::kShape);
  EXPECT_EQ(s.primitives[0].material, 0);
  ASSERT_EQ(s.materials.size(), 2u);  // "red" and the appended glTF default
  EXPECT_EQ(s.primitives[1].material, 1);
  EXPECT_EQ(s.materials[1].metallic, 1.0f);
  Bounds3 sphere = s.primitives[0].shape->bounds();
  EXPECT_FLOAT_EQ(sphere.hi.x, 2.5f);
  EXPECT_FLOAT_EQ(s.primitives[2].shape->bounds().lo.z, -3.0f);
  EXPECT_FALSE(s.primitives[1].shape->bounds().finite());
}

TEST(GltfTiny, TrayShapeErrors) {
  auto shapeError = [](const std::string& shape) {
    return errorOf(
        [&] { TinyDoc().load(R"("nodes":[{"extensions":{"TRAY_shape":)" + shape + "}}]"); });
  };
  EXPECT_NE(shapeError(R"({"type":"sphere","radus":1})").find("unknown key 'radus'"),
            std::string::npos);
  EXPECT_NE(shapeError(R"({"type":"sphere","radius":0})").find("radius"), std::string::npos);
  EXPECT_NE(shapeError(R"({"type":"box","min":[0,0,0],"max":[1,0,1]})").find("'min'"),
            std::string::npos);
  EXPECT_NE(shapeError(R"({"type":"teapot"})").find("unknown TRAY_shape type 'teapot'"),
            std::string::npos);
  EXPECT_NE(shapeError(R"({"type":"sphere","material":3})").find("missing material 3"),
            std::string::npos);
}

TEST(GltfTiny, TrayPhongAndPriority) {
  Scene s = TinyDoc().load(R"("materials":[
      {"extensions":{"TRAY_materials_phong":{"diffuse":[0.1,0.2,0.3],"shininess":8,"reflectance":0.5},
                     "TRAY_materials_priority":{"priority":3}}},
      {"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.5,0.5,1],"metallicFactor":0}}])");
  ASSERT_EQ(s.materials.size(), 2u);
  const Material& a = s.materials[0];
  EXPECT_TRUE(a.hasPhong);
  expectNear(a.phong.diffuse, {0.1f, 0.2f, 0.3f});
  EXPECT_EQ(a.phong.shininess, 8.0f);
  EXPECT_EQ(a.phong.reflectance, 0.5f);
  EXPECT_EQ(a.phong.transmittance, PhongParams().transmittance);  // default kept
  expectNear(a.phong.specular, PhongParams().specular);
  EXPECT_EQ(a.priority, 3);
  const Material& b = s.materials[1];
  EXPECT_FALSE(b.hasPhong);
  expectNear(b.phong.diffuse, phongFromPbr(b).diffuse);
  expectNear(b.phong.diffuse, {0.5f, 0.5f, 0.5f});
  std::string e = errorOf([] {
    TinyDoc().load(R"("materials":[{"extensions":{"TRAY_materials_phong":{"difuse":[1,1,1]}}}])");
  });
  EXPECT_NE(e.find("unknown key 'difuse'"), std::string::npos) << e;
}

TEST(GltfTiny, KhrMaterialExtensionsAndTextures) {
  // The image is a real 1x1 PNG: images that materials use are decoded at load.
  Scene s = TinyDoc().load(
      R"("images":[{"uri":"data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGNoaGgAAAMEAYFL09IQAAAAAElFTkSuQmCC"}],
      "textures":[{"source":0},{"source":0}],"materials":[{
      "emissiveFactor":[1,0.5,0],"doubleSided":true,
      "normalTexture":{"index":1,"texCoord":1,"scale":0.5},
      "pbrMetallicRoughness":{"baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":
          {"offset":[0.25,0.5],"scale":[2,3],"rotation":0.5}}}},
      "extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":4},
                    "KHR_materials_transmission":{"transmissionFactor":0.75},
                    "KHR_materials_ior":{"ior":1.33}}}])");
  const Material& m = s.materials.at(0);
  expectNear(m.emissive, {4, 2, 0});
  EXPECT_FLOAT_EQ(m.transmission, 0.75f);
  EXPECT_FLOAT_EQ(m.ior, 1.33f);
  EXPECT_TRUE(m.doubleSided);
  EXPECT_EQ(m.baseColorTexture.image, 0);
  EXPECT_FLOAT_EQ(m.baseColorTexture.offset.y, 0.5f);
  EXPECT_FLOAT_EQ(m.baseColorTexture.scaleUV.y, 3.0f);
  EXPECT_FLOAT_EQ(m.baseColorTexture.rotation, 0.5f);
  EXPECT_EQ(m.normalTexture.image, 1);
  EXPECT_EQ(m.normalTexture.texCoord, 1);
  EXPECT_FLOAT_EQ(m.normalTexture.scale, 0.5f);
  EXPECT_EQ(m.emissiveTexture.image, -1);
}

TEST(GltfTiny, MaterialLayerExtensions) {
  Scene s = TinyDoc().load(
      R"("images":[{"uri":"data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGNoaGgAAAMEAYFL09IQAAAAAElFTkSuQmCC"}],
      "textures":[{"source":0}],"materials":[{"extensions":{
      "KHR_materials_transmission":{"transmissionFactor":1},
      "KHR_materials_volume":{"thicknessFactor":0.5,"attenuationColor":[0.5,0.25,1],
                              "attenuationDistance":2},
      "KHR_materials_specular":{"specularFactor":0.5,"specularColorFactor":[1,0.5,2],
                                "specularColorTexture":{"index":0}},
      "KHR_materials_clearcoat":{"clearcoatFactor":0.75,"clearcoatRoughnessFactor":0.25,
          "clearcoatNormalTexture":{"index":0,"scale":0.5,"texCoord":1}},
      "KHR_materials_sheen":{"sheenColorFactor":[0.9,0.7,0.6],"sheenRoughnessFactor":0.6,
                             "sheenRoughnessTexture":{"index":0}}}},{}])");
  const MaterialLayers& l = s.materials.at(0).layers;
  EXPECT_FLOAT_EQ(l.thickness, 0.5f);
  expectNear(l.attenuationColor, {0.5f, 0.25f, 1});
  EXPECT_FLOAT_EQ(l.attenuationDistance, 2.0f);
  EXPECT_NEAR(l.absorption().x, std::log(2.0f) / 2, 1e-6f);
  EXPECT_FLOAT_EQ(l.specular, 0.5f);
  expectNear(l.specularColor, {1, 0.5f, 2});
  EXPECT_TRUE(l.specularColorTexture.valid());
  EXPECT_FLOAT_EQ(l.clearcoat, 0.75f);
  EXPECT_FLOAT_EQ(l.clearcoatRoughness, 0.25f);
  EXPECT_EQ(l.clearcoatNormalTexture.texCoord, 1);
  EXPECT_FLOAT_EQ(l.clearcoatNormalTexture.scale, 0.5f);
  expectNear(l.sheenColor, {0.9f, 0.7f, 0.6f});
  EXPECT_FLOAT_EQ(l.sheenRoughness, 0.6f);
  EXPECT_TRUE(l.sheenRoughnessTexture.valid());
  EXPECT_TRUE(s.materials.at(0).hasTextures());
  // Without the extensions: the defaults, which change nothing.
  const MaterialLayers& none = s.materials.at(1).layers;
  EXPECT_FALSE(none.hasSpecular() || none.hasTextures() || none.clearcoat > 0);
  EXPECT_TRUE(isBlack(none.absorption()));

  auto error = [](const std::string& ext) {
    return errorOf([&] { TinyDoc().load(R"("materials":[{"extensions":{)" + ext + "}}]"); });
  };
  std::string e = error(R"("KHR_materials_clearcoat":{"clearcoatFactor":1.5})");
  EXPECT_NE(e.find("KHR_materials_clearcoat 'clearcoatFactor'"), std::string::npos) << e;
  e = error(R"("KHR_materials_specular":{"specularFactor":-1})");
  EXPECT_NE(e.find("KHR_materials_specular 'specularFactor'"), std::string::npos) << e;
  e = error(R"("KHR_materials_sheen":{"sheenRoughnessFactor":2})");
  EXPECT_NE(e.find("KHR_materials_sheen 'sheenRoughnessFactor'"), std::string::npos) << e;
  e = error(R"("KHR_materials_volume":{"attenuationDistance":0})");
  EXPECT_NE(e.find("KHR_materials_volume 'attenuationDistance' must be positive"),
            std::string::npos)
      << e;
  e = error(R"("KHR_materials_volume":{"attenuationColor":[2,0,0]})");
  EXPECT_NE(e.find("'attenuationColor'"), std::string::npos) << e;
  e = error(R"("KHR_materials_clearcoat":{"clearcoatTexture":{"index":7}})");
  EXPECT_NE(e.find("clearcoatTexture refers to missing texture 7"), std::string::npos) << e;
}

TEST(GltfTiny, TrayEnvironment) {
  Scene s = TinyDoc().load(R"("scene":0,"scenes":[{"extensions":{"TRAY_environment":
      {"ambient":[0.1,0.2,0.3],"background":[1,2,3]}}}])");
  expectNear(s.environment.ambient, {0.1f, 0.2f, 0.3f});
  expectNear(s.environment.background, {1, 2, 3});
  Scene none = TinyDoc().load(R"("scenes":[{}])");
  expectNear(none.environment.background, {0, 0, 0});
}

TEST(GltfTiny, PunctualLights) {
  Scene s = TinyDoc().load(R"("extensions":{"KHR_lights_punctual":{"lights":[
      {"type":"point","color":[1,0.5,0.25],"intensity":8},
      {"type":"spot","intensity":2,"spot":{"innerConeAngle":0.1,"outerConeAngle":0.5}},
      {"type":"directional","color":[0,1,0]}]}},
      "scenes":[{"nodes":[0,1,2]}],"nodes":[
      {"translation":[1,2,3],"extensions":{"KHR_lights_punctual":{"light":0}}},
      {"translation":[0,5,0],"rotation":[-0.70710678,0,0,0.70710678],
       "extensions":{"KHR_lights_punctual":{"light":1}}},
      {"scale":[3,3,3],"extensions":{"KHR_lights_punctual":{"light":2}}}])");
  ASSERT_EQ(s.lights.size(), 3u);
  EXPECT_EQ(s.lights[0].type, PunctualLightDesc::Type::kPoint);
  expectNear(s.lights[0].intensity, {8, 4, 2});
  expectNear(s.lights[0].position, {1, 2, 3});
  EXPECT_EQ(s.lights[1].type, PunctualLightDesc::Type::kSpot);
  expectNear(s.lights[1].intensity, {2, 2, 2});
  expectNear(s.lights[1].direction, {0, -1, 0});  // -Z turned -90 deg about X points down
  EXPECT_FLOAT_EQ(s.lights[1].innerConeAngle, 0.1f);
  EXPECT_FLOAT_EQ(s.lights[1].outerConeAngle, 0.5f);
  EXPECT_EQ(s.lights[2].type, PunctualLightDesc::Type::kDirectional);
  expectNear(s.lights[2].intensity, {0, 1, 0});
  expectNear(s.lights[2].direction, {0, 0, -1});  // normalized despite the scale
}

TEST(GltfTiny, InstancedMeshIsStoredOnce) {
  Scene s = triangleDoc().load(kTriangleMesh + R"(,"scenes":[{"nodes":[0,1]}],
      "nodes":[{"mesh":0},{"mesh":0,"translation":[5,0,0]}])");
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.primitives.size(), 2u);
  EXPECT_EQ(s.primitives[0].mesh, 0u);
  EXPECT_EQ(s.primitives[1].mesh, 0u);
  EXPECT_EQ(s.primitives[1].objectId, 1);
  EXPECT_EQ(s.meshes[0].material, 0);  // the appended default material
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
}

TEST(GltfTiny, SceneSelection) {
  const std::string rest = kTriangleMesh + R"(,"scene":1,"scenes":[{"nodes":[0]},{"nodes":[1,2]}],
      "nodes":[{"mesh":0},{"mesh":0},{"mesh":0}])";
  EXPECT_EQ(triangleDoc().load(rest).primitives.size(), 2u);
  LoadOptions first;
  first.scene = 0;
  EXPECT_EQ(triangleDoc().load(rest, first).primitives.size(), 1u);
  LoadOptions missing;
  missing.scene = 2;
  EXPECT_NE(errorOf([&] { triangleDoc().load(rest, missing); }).find("scene 2 does not exist"),
            std::string::npos);
}

}  // namespace
}  // namespace tray

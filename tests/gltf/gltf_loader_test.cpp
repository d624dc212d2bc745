// loadGltf on every shared sample (counts checked against an independent reading) and on tiny
// glTF documents written to a temporary folder, one feature each.
#include "gltf/gltf_loader.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "core/error.h"
#include "tests/base64.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

namespace fs = std::filesystem;

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
// Tiny documents. TinyDoc packs data into one base64 buffer and writes the file into a fresh
// temporary folder (never the source tree).

using tray::test::base64;

fs::path freshFolder() {
  static std::atomic<int> counter{0};
  fs::path dir = tray::test::testDir() / ("doc" + std::to_string(counter++));
  fs::create_directories(dir);
  return dir;
}

class TinyDoc {
 public:
  /// Adds raw bytes as bufferView + accessor; returns the accessor index.
  template <typename T>
  int add(const std::vector<T>& values, int componentType, const char* type,
          bool normalized = false, int components = 1, const std::string& extra = "") {
    while (bytes_.size() % 4) bytes_ += '\0';
    size_t offset = bytes_.size();
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    views_ += sep(views_) + "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
              ",\"byteLength\":" + std::to_string(values.size() * sizeof(T)) + "}";
    int view = viewCount_++;
    accessors_ += sep(accessors_) + "{\"bufferView\":" + std::to_string(view) +
                  ",\"componentType\":" + std::to_string(componentType) + ",\"type\":\"" + type +
                  "\",\"count\":" + std::to_string(values.size() / size_t(components)) +
                  (normalized ? ",\"normalized\":true" : "") + extra + "}";
    return accessorCount_++;
  }
  int vec3(const std::vector<float>& v) { return add(v, 5126, "VEC3", false, 3); }
  int indices(const std::vector<uint16_t>& v) { return add(v, 5123, "SCALAR"); }
  /// The document with `rest` (scenes, nodes, meshes, ...) appended to the root object.
  std::string json(const std::string& rest) const {
    std::string buffer = bytes_.empty()
                             ? ""
                             : "\"buffers\":[{\"byteLength\":" + std::to_string(bytes_.size()) +
                                   ",\"uri\":\"data:application/octet-stream;base64," +
                                   base64(bytes_) + "\"}],";
    std::string s = "{\"asset\":{\"version\":\"2.0\"}," + buffer;
    if (viewCount_) s += "\"bufferViews\":[" + views_ + "],\"accessors\":[" + accessors_ + "],";
    return s + rest + "}";
  }
  /// Writes the document as `name` in a fresh folder and loads it.
  Scene load(const std::string& rest, const LoadOptions& options = {}, LoadReport* report = nullptr,
             const std::string& name = "scene.gltf") const {
    fs::path file = freshFolder() / name;
    std::ofstream(file) << json(rest);
    return loadGltf(file.string(), options, report);
  }

 private:
  static std::string sep(const std::string& s) { return s.empty() ? "" : ","; }
  std::string bytes_, views_, accessors_;
  int viewCount_ = 0, accessorCount_ = 0;
};

/// A document with one triangle mesh (accessor 0 positions, 1 indices) as mesh 0.
TinyDoc triangleDoc() {
  TinyDoc d;
  d.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  d.indices({0, 1, 2});
  return d;
}
const std::string kTriangleMesh =
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}])";

void expectNear(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
  EXPECT_NEAR(a.z, b.z, 1e-5f);
}

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

TEST(GltfTiny, DegenerateTrianglesDroppedAndBadNormalsZeroed) {
  TinyDoc d;
  d.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0});
  d.indices({0, 1, 2, 0, 1, 3, 0, 0, 2});  // the 2nd is collinear, the 3rd repeats a vertex
  float nan = std::nanf("");
  d.vec3({0, 0, 1, nan, 0, 1, 0, 0, 1, 0, 0, 1});
  LoadReport report;
  Scene s = d.load(R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{"primitives":[
      {"attributes":{"POSITION":0,"NORMAL":2},"indices":1}]}])",
                   {}, &report);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].triangleCount(), 1u);
  expectNear(s.meshes[0].normals[1], {0, 0, 0});
  ASSERT_EQ(report.warnings.size(), 2u);
  EXPECT_NE(report.warnings[0].find("dropped 2 degenerate"), std::string::npos);
  EXPECT_NE(report.warnings[1].find("replaced 1 non-finite"), std::string::npos);
}

// glTF-Validator reports data outside an accessor's declared min/max as an error; rendering
// survives it (TRay uses the data), so it is one warning naming the accessor, not a refusal, and
// bounds that hold (also unnormalized ones of a normalized accessor, §5.1.7) say nothing.
TEST(GltfTiny, DataOutsideMinMaxIsOneWarningNamingTheAccessor) {
  const std::string rest = R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],"meshes":[{
      "primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":2},"indices":1}]}])";
  for (const bool lying : {false, true}) {
    TinyDoc d;
    d.add<float>({0, 0, 0, 1, 0, 0, 0, 1, 0}, 5126, "VEC3", false, 3,
                 lying ? R"(,"min":[0,0,0],"max":[1,0.5,0])" : R"(,"min":[0,0,0],"max":[1,1,0])");
    d.indices({0, 1, 2});
    d.add<uint8_t>({0, 0, 255, 0, 0, 255}, 5121, "VEC2", true, 2,
                   R"(,"min":[0,0],"max":[255,255])");
    LoadReport report;
    const Scene s = d.load(rest, {}, &report);
    ASSERT_EQ(s.meshes.size(), 1u);
    expectNear(s.meshes[0].positions[2], {0, 1, 0});  // the data, not the declared bound
    if (!lying) {
      EXPECT_TRUE(report.warnings.empty()) << report.warnings[0];
      continue;
    }
    ASSERT_EQ(report.warnings.size(), 1u);
    EXPECT_NE(report.warnings[0].find("accessor 0 has data outside its declared min/max"),
              std::string::npos)
        << report.warnings[0];
    EXPECT_NE(report.warnings[0].find("element 2 component 1"), std::string::npos)
        << report.warnings[0];
  }
}

TEST(GltfTiny, NanPositionNamesTheAccessor) {
  TinyDoc d;
  d.vec3({0, 0, 0, std::nanf(""), 0, 0, 0, 1, 0});
  std::string e =
      errorOf([&] { d.load(R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}])"); });
  EXPECT_NE(e.find("scene.gltf: accessor 0 (POSITION) has a NaN"), std::string::npos) << e;
}

TEST(GltfTiny, UnknownExtensions) {
  std::string e = errorOf([] {
    TinyDoc().load(R"("extensionsUsed":["EXT_magic"],"extensionsRequired":["EXT_magic"])");
  });
  EXPECT_NE(e.find("required extension 'EXT_magic'"), std::string::npos) << e;
  LoadOptions ignore;
  ignore.ignoreRequiredExtensions = true;
  LoadReport anyway;
  TinyDoc().load(R"("extensionsUsed":["EXT_magic"],"extensionsRequired":["EXT_magic"])", ignore,
                 &anyway);
  ASSERT_EQ(anyway.warnings.size(), 1u);  // one line, not a second "not supported" one
  EXPECT_NE(anyway.warnings[0].find("required extension 'EXT_magic' is not supported: rendering"),
            std::string::npos);
  LoadReport report;
  TinyDoc().load(R"("extensionsUsed":["EXT_magic","KHR_materials_volume","EXT_other"])", {},
                 &report);
  ASSERT_EQ(report.warnings.size(), 2u);
  EXPECT_NE(report.warnings[0].find("'EXT_magic'"), std::string::npos);
  EXPECT_NE(report.warnings[1].find("'EXT_other'"), std::string::npos);
}

TEST(GltfTiny, AKnownButUnsupportedExtensionIsRefusedWithItsReason) {
  // SpecGlossVsMetalRough of the Khronos samples requires it (docs/gallery/khronos).
  std::string e = errorOf([] {
    TinyDoc().load(R"("extensionsUsed":["KHR_materials_pbrSpecularGlossiness"],)"
                   R"("extensionsRequired":["KHR_materials_pbrSpecularGlossiness"])");
  });
  EXPECT_NE(e.find("required extension 'KHR_materials_pbrSpecularGlossiness' is not supported: "
                   "archived by Khronos"),
            std::string::npos)
      << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << "one line";
  LoadReport report;
  TinyDoc().load(R"("extensionsUsed":["KHR_draco_mesh_compression"])", {}, &report);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("ignored (TRay decodes no Draco"), std::string::npos)
      << report.warnings[0];
}

TEST(GltfTiny, PathTraversalRefusedUnlessAllowed) {
  fs::path root = freshFolder();
  fs::create_directories(root / "scene");
  std::string triangle(36, '\0');
  float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::memcpy(triangle.data(), xyz, 36);
  std::ofstream(root / "outside.bin", std::ios::binary) << triangle;
  fs::path file = root / "scene" / "scene.gltf";
  std::ofstream(file) << R"({"asset":{"version":"2.0"},"buffers":[{"uri":"../outside.bin",
      "byteLength":36}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,
      "componentType":5126,"type":"VEC3","count":3}],"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
      "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]})";
  std::string e = errorOf([&] { loadGltf(file.string()); });
  EXPECT_NE(e.find("'../outside.bin'"), std::string::npos) << e;
  LoadOptions any;
  any.allowAnyPath = true;
  EXPECT_EQ(loadGltf(file.string(), any).meshes.size(), 1u);
  // Percent-encoded dots are decoded before the check, so they are refused the same way.
  std::ofstream(root / "scene" / "encoded.gltf") << R"({"asset":{"version":"2.0"},
      "buffers":[{"uri":"%2e%2e/outside.bin","byteLength":36}]})";
  e = errorOf([&] { loadGltf((root / "scene" / "encoded.gltf").string()); });
  EXPECT_NE(e.find("'..'"), std::string::npos) << e;
}

TEST(GltfTiny, GraphErrors) {
  auto error = [](const std::string& rest) { return errorOf([&] { TinyDoc().load(rest); }); };
  EXPECT_NE(error(R"("nodes":[{"children":[2]},{"children":[2]},{}])").find("two parents"),
            std::string::npos);
  EXPECT_NE(error(R"("scenes":[{"nodes":[1]}],"nodes":[{"children":[1]},{}])").find("not a root"),
            std::string::npos);
  EXPECT_NE(error(R"("nodes":[{"translation":[1e39,0,0]}])").find("NaN or infinity"),
            std::string::npos);
  EXPECT_NE(error(R"("cameras":[{"type":"perspective","perspective":{"yfov":0,"znear":1}}])")
                .find("camera 0 yfov"),
            std::string::npos);
}

TEST(GltfTiny, DeepJsonRefusedBeforeParsing) {
  // Recursive JSON parsers would overflow the stack on this; the loader must refuse it first.
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::string e = errorOf([&] { TinyDoc().load("\"extras\":" + deep); });
  EXPECT_NE(e.find("nests deeper"), std::string::npos) << e;
}

TEST(GltfTiny, MisalignedAccessorRefused) {
  TinyDoc d;
  d.add(std::vector<uint8_t>(40, 0), 5121, "SCALAR");
  std::string doc = d.json(R"("scenes":[{}])");
  // Re-point the accessor as floats at byte 1 of its view: not 4-byte aligned.
  doc.replace(doc.find("\"componentType\":5121"), 20, "\"componentType\":5126,\"byteOffset\":1");
  fs::path file = freshFolder() / "scene.gltf";
  std::ofstream(file) << doc;
  std::string e = errorOf([&] { loadGltf(file.string()); });
  EXPECT_NE(e.find("not aligned"), std::string::npos) << e;
}

}  // namespace
}  // namespace tray

namespace tray {
namespace {

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

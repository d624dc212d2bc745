// loadGltf on tiny glTF documents that are wrong or suspicious (tests/gltf/tiny_doc.h): each is
// refused or warned in one line naming the file and the problem.
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

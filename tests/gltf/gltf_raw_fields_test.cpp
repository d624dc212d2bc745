// Numbers that tinygltf 2.7.0 would coerce silently (a negative byteOffset read as 0, -1 as "no
// material", 0.5 truncated, "0" skipped, 1e20 cast out of range) are refused with one line that
// names the field. Each case edits one field of a small valid document written by the test.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "tests/base64.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// One triangle (positions at byte 0, uint16 indices at byte 36) with a material, a camera and
/// a node for each.
json validDoc() {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t indices[4] = {0, 1, 2, 0};  // padded to 4 bytes
  std::string bytes(reinterpret_cast<const char*>(positions), sizeof(positions));
  bytes.append(reinterpret_cast<const char*>(indices), sizeof(indices));
  json doc = json::parse(R"({
    "asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0.2, 0.2, 2]}],
    "cameras": [{"type": "perspective",
                 "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 1.5}}],
    "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 3,
       "min": [0, 0, 0], "max": [1, 1, 0]},
      {"bufferView": 1, "componentType": 5123, "type": "SCALAR", "count": 3}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 6}]})");
  json buffer = json::object();
  buffer["byteLength"] = bytes.size();
  buffer["uri"] = "data:application/octet-stream;base64," + test::base64(bytes);
  doc["buffers"] = json::array();
  doc["buffers"].push_back(buffer);
  return doc;
}

/// Loads `doc` from a fresh folder; returns the error message ("" if it loaded).
std::string loadError(const json& doc) {
  static std::atomic<int> counter{0};
  const fs::path dir = test::testDir() / ("doc" + std::to_string(counter++));
  fs::create_directories(dir);
  const fs::path file = dir / "doc.gltf";
  std::ofstream(file) << doc.dump();
  try {
    loadGltf(file.string());
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), Error::Kind::kInput);
    return e.what();
  }
  return "";
}

TEST(GltfRawFields, TheValidDocumentLoads) {
  EXPECT_EQ(loadError(validDoc()), "");
  json stride = validDoc();  // byteStride 12 (a multiple of 4 within 4..252) is fine
  stride["bufferViews"][0]["byteStride"] = 12;
  EXPECT_EQ(loadError(stride), "");
}

struct BadField {
  const char* pointer;  ///< JSON pointer of the field
  json value;
  const char* named;  ///< how the message names the field
};

void PrintTo(const BadField& b, std::ostream* os) {
  *os << b.named << " = " << b.value.dump();
}

class GltfRawFieldsBad : public ::testing::TestWithParam<BadField> {};

TEST_P(GltfRawFieldsBad, IsAnErrorNamingTheField) {
  json doc = validDoc();
  doc[json::json_pointer(GetParam().pointer)] = GetParam().value;
  const std::string message = loadError(doc);
  ASSERT_NE(message, "") << GetParam().named << " = " << GetParam().value.dump() << " loaded";
  EXPECT_NE(message.find("doc.gltf: "), std::string::npos) << message;
  EXPECT_NE(message.find(GetParam().named), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Issue18, GltfRawFieldsBad,
    ::testing::Values(
        BadField{"/bufferViews/0/byteOffset", -64, "bufferViews[0].byteOffset"},
        BadField{"/bufferViews/0/byteOffset", 1e20, "bufferViews[0].byteOffset"},
        BadField{"/bufferViews/0/byteOffset", 0.5, "bufferViews[0].byteOffset"},
        BadField{"/bufferViews/0/byteOffset", "0", "bufferViews[0].byteOffset"},
        BadField{"/accessors/0/byteOffset", -12, "accessors[0].byteOffset"},
        BadField{"/accessors/0/byteOffset", 1e20, "accessors[0].byteOffset"},
        BadField{"/accessors/1/count", -3, "accessors[1].count"},
        BadField{"/bufferViews/0/byteStride", -12, "bufferViews[0].byteStride"},
        BadField{"/bufferViews/0/byteStride", 256, "bufferViews[0].byteStride"},
        BadField{"/bufferViews/0/byteStride", 14, "bufferViews[0].byteStride"},
        BadField{"/meshes/0/primitives/0/indices", -1, "meshes[0].primitives[0].indices"},
        BadField{"/meshes/0/primitives/0/material", -1, "meshes[0].primitives[0].material"},
        BadField{"/meshes/0/primitives/0/attributes/POSITION", -1,
                 "meshes[0].primitives[0].attributes.POSITION"},
        BadField{"/nodes/0/mesh", -1, "nodes[0].mesh"},
        BadField{"/nodes/1/camera", 0.5, "nodes[1].camera"},
        BadField{"/scenes/0/nodes/1", -1, "scenes[0].nodes[1]"},
        BadField{"/cameras/0/perspective/aspectRatio", 0, "cameras[0].perspective.aspectRatio"},
        BadField{"/cameras/0/perspective/aspectRatio", 1e-30, "cameras[0].perspective.aspectRatio"},
        BadField{"/cameras/0/perspective/aspectRatio", "1.5",
                 "cameras[0].perspective.aspectRatio"}),
    [](const ::testing::TestParamInfo<BadField>& info) {
      return "Case" + std::to_string(info.index);
    });

}  // namespace
}  // namespace tray

#pragma once
// Tiny glTF documents for loader tests: TinyDoc packs accessors into one base64 buffer and
// writes the file into a fresh temporary folder (never the source tree), then loads it.
#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/math.h"
#include "gltf/gltf_loader.h"
#include "tests/base64.h"
#include "tests/temp_dir.h"

namespace tray::test {

namespace fs = std::filesystem;

inline fs::path freshFolder() {
  static std::atomic<int> counter{0};
  fs::path dir = testDir() / ("doc" + std::to_string(counter++));
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
inline TinyDoc triangleDoc() {
  TinyDoc d;
  d.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
  d.indices({0, 1, 2});
  return d;
}
inline const std::string kTriangleMesh =
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}])";

inline void expectNear(const Vec3& a, const Vec3& b) {
  EXPECT_NEAR(a.x, b.x, 1e-5f);
  EXPECT_NEAR(a.y, b.y, 1e-5f);
  EXPECT_NEAR(a.z, b.z, 1e-5f);
}

}  // namespace tray::test

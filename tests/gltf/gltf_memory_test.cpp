// loadGltfFromMemory, the fuzzer's entry point: the same scene as from the file, external URIs
// refused, and every fuzzer reproducer in fuzz/regressions/ handled without a crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace tray {
namespace {

const fs::path kSamples = fs::path(TRAY_SHARED_DIR) / "gltf-samples";

std::vector<unsigned char> bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

Scene fromMemory(const fs::path& p) {
  const auto bytes = bytesOf(p);
  return loadGltfFromMemory(bytes.data(), bytes.size(), p.filename().string());
}

size_t triangles(const Scene& s) {
  size_t n = 0;
  for (const auto& m : s.meshes) n += m.triangleCount();
  return n;
}

TEST(GltfMemory, GlbAndDataUriScenesLoadAsFromTheirFiles) {
  for (const char* name : {"Box.glb", "Duck.glb", "SimpleSparseAccessor.gltf", "Cameras.gltf"}) {
    const Scene a = loadGltf((kSamples / name).string()), b = fromMemory(kSamples / name);
    EXPECT_GT(triangles(a), 0u) << name;
    EXPECT_EQ(triangles(a), triangles(b)) << name;
    EXPECT_EQ(a.primitives.size(), b.primitives.size()) << name;
    EXPECT_EQ(a.cameras.size(), b.cameras.size()) << name;
  }
}

TEST(GltfMemory, ExternalUrisAreRefusedEvenWithAllowAnyPath) {
  LoadOptions any;
  any.allowAnyPath = true;
  const auto bytes = bytesOf(kSamples / "Avocado" / "Avocado.gltf");
  try {
    loadGltfFromMemory(bytes.data(), bytes.size(), "avocado-in-memory", any);
    FAIL() << "an external buffer URI was read";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("avocado-in-memory: ", 0), 0u) << m;
    EXPECT_NE(m.find("Avocado.bin"), std::string::npos) << m;
    EXPECT_NE(m.find("only use data: URIs"), std::string::npos) << m;
  }
}

TEST(GltfMemory, EmptyInputIsRefused) {
  EXPECT_THROW(loadGltfFromMemory(nullptr, 0, "empty"), Error);
}

/// One triangle mesh of `primitives` primitives, placed by `nodes` nodes.
std::string instancedScene(int primitives, int nodes) {
  std::string prims, nodeList, roots;
  for (int i = 0; i < primitives; ++i)
    prims += std::string(i ? "," : "") + "{\"attributes\":{\"POSITION\":0}}";
  for (int i = 0; i < nodes; ++i) {
    nodeList += std::string(i ? "," : "") + "{\"mesh\":0}";
    roots += std::string(i ? "," : "") + std::to_string(i);
  }
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" + roots +
         R"(]}],"nodes":[)" + nodeList + R"(],"meshes":[{"primitives":[)" + prims +
         R"(]}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",)"
         R"("min":[0,0,0],"max":[1,1,0]}],"bufferViews":[{"buffer":0,"byteLength":36}],)"
         R"("buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)"
         R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]})";
}

TEST(GltfMemory, PlacedObjectsAreCapped) {
  // 1000 x 1000 = 1e6 instances load; one node more passes the cap of 1e6 placed objects.
  const std::string ok = instancedScene(1000, 1000), tooMany = instancedScene(1000, 1001);
  const auto* okBytes = reinterpret_cast<const unsigned char*>(ok.data());
  EXPECT_EQ(loadGltfFromMemory(okBytes, ok.size(), "ok.gltf").primitives.size(), 1000000u);
  try {
    loadGltfFromMemory(reinterpret_cast<const unsigned char*>(tooMany.data()), tooMany.size(),
                       "many.gltf");
    FAIL() << "1001000 placed objects loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("more than 1000000 objects"), std::string::npos)
        << e.what();
  }
}

/// A folder of its own in the test's folder.
fs::path freshFolder(const std::string& name) {
  const fs::path dir = test::testDir() / name;
  fs::create_directories(dir);
  return dir;
}

/// `copies` buffers naming the same file `uri` of `length` bytes, one bufferView and one mesh
/// (a triangle of 3 VEC3 floats at the view's start) per buffer.
std::string sharedBufferScene(int copies, uint64_t length) {
  std::string buffers, views, accessors, meshes, nodes, roots;
  for (int i = 0; i < copies; ++i) {
    const std::string c = i ? "," : "", n = std::to_string(i);
    buffers += c + R"({"uri":"shared.bin","byteLength":)" + std::to_string(length) + "}";
    views += c + R"({"buffer":)" + n + R"(,"byteLength":36})";
    accessors += c + R"({"bufferView":)" + n +
                 R"(,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]})";
    meshes += c + R"({"primitives":[{"attributes":{"POSITION":)" + n + "}}]}";
    nodes += c + R"({"mesh":)" + n + "}";
    roots += c + n;
  }
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" + roots +
         R"(]}],"nodes":[)" + nodes + R"(],"meshes":[)" + meshes + R"(],"accessors":[)" +
         accessors + R"(],"bufferViews":[)" + views + R"(],"buffers":[)" + buffers + "]}";
}

TEST(GltfMemory, BuffersNamingOneFileAreReadOnceAndSeeItsBytes) {
  const fs::path dir = freshFolder("shared");
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::ofstream(dir / "shared.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(triangle), sizeof triangle);
  std::ofstream(dir / "shared.gltf") << sharedBufferScene(3, 36);
  LoadReport report;
  const Scene s = loadGltf((dir / "shared.gltf").string(), {}, &report);
  ASSERT_EQ(s.meshes.size(), 3u);
  for (const auto& m : s.meshes) {
    ASSERT_EQ(m.triangleCount(), 1u);
    EXPECT_EQ(m.positions[1].x, 1.0f);
    EXPECT_EQ(m.positions[2].y, 1.0f);
  }
  EXPECT_EQ(report.memory.buffers, 36u);  // the file once, not three times
}

/// `json` as a .glb (glTF 2.0 §4.4) with `bin` as its BIN chunk (none if empty).
std::string glbOf(std::string json, const std::string& bin) {
  while (json.size() % 4) json += ' ';
  auto u32 = [](uint64_t v) {
    std::string out(4, '\0');
    for (int i = 0; i < 4; ++i) out[size_t(i)] = char((v >> (8 * i)) & 0xff);
    return out;
  };
  std::string body = u32(json.size()) + "JSON" + json;
  if (!bin.empty()) body += u32(bin.size()) + std::string("BIN\0", 4) + bin;
  return "glTF" + u32(2) + u32(12 + body.size()) + body;
}

// A .glb whose JSON names one external file in three buffers, beside its own BIN chunk: the
// file is read once (the container is rebuilt around the merged JSON, since the BIN chunk it
// copies is smaller than the two reads saved), and every mesh still sees its own bytes.
TEST(GltfMemory, GlbBuffersNamingOneFileAreReadOnceBesideItsBinChunk) {
  const fs::path dir = freshFolder("shared_glb");
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  std::string file(reinterpret_cast<const char*>(triangle), sizeof triangle);
  file.resize(400, '\0');
  std::ofstream(dir / "shared.bin", std::ios::binary) << file;
  const float binTriangle[9] = {0, 0, 0, 2, 0, 0, 0, 2, 0};
  const std::string bin(reinterpret_cast<const char*>(binTriangle), sizeof binTriangle);
  std::string buffers = R"({"byteLength":36})", views, accessors, meshes, nodes, roots;
  for (int i = 0; i < 4; ++i) {
    const std::string c = i ? "," : "", n = std::to_string(i);
    if (i) buffers += R"(,{"uri":"shared.bin","byteLength":400})";
    views += c + R"({"buffer":)" + n + R"(,"byteLength":36})";
    accessors += c + R"({"bufferView":)" + n + R"(,"componentType":5126,"count":3,"type":"VEC3"})";
    meshes += c + R"({"primitives":[{"attributes":{"POSITION":)" + n + "}}]}";
    nodes += c + R"({"mesh":)" + n + "}";
    roots += c + n;
  }
  const std::string json = R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[)" + roots +
                           R"(]}],"nodes":[)" + nodes + R"(],"meshes":[)" + meshes +
                           R"(],"accessors":[)" + accessors + R"(],"bufferViews":[)" + views +
                           R"(],"buffers":[)" + buffers + "]}";
  std::ofstream(dir / "shared.glb", std::ios::binary) << glbOf(json, bin);
  LoadReport report;
  const Scene s = loadGltf((dir / "shared.glb").string(), {}, &report);
  ASSERT_EQ(s.meshes.size(), 4u);
  float xs = 0;
  for (const auto& m : s.meshes) {
    ASSERT_EQ(m.triangleCount(), 1u);
    xs += m.positions[1].x;
  }
  EXPECT_EQ(xs, 2.0f + 1 + 1 + 1);  // the BIN chunk's triangle and the file's three times
  // The file once (400) plus the BIN chunk (36) and its rebuilt copy (44): not 3 x 400.
  EXPECT_EQ(report.memory.buffers, 480u);
}

TEST(GltfMemory, MaxMemoryRefusesHugeBuffersBeforeReadingThem) {
  // Issue 18: a 700-byte file naming one 1.5 GiB buffer four times read it into four vectors
  // and peaked at 3.3 GB before the 4 GiB cap on URI bytes refused it. A sparse file costs no
  // disk; the refusal comes from the JSON alone, before any byte is read.
  const fs::path dir = freshFolder("huge");
  const uint64_t length = uint64_t(1536) << 20;
  std::ofstream(dir / "shared.bin").close();
  fs::resize_file(dir / "shared.bin", length);
  std::ofstream(dir / "huge.gltf") << sharedBufferScene(4, length);
  LoadOptions options;
  options.maxMemoryBytes = uint64_t(1000) << 20;
  try {
    loadGltf((dir / "huge.gltf").string(), options);
    FAIL() << "1.5 GiB of buffers loaded under --max-memory 1000";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("huge.gltf: needs about 1536 MB (buffers 1536 MB, textures 0 MB"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("more than --max-memory 1000 MB"), std::string::npos) << m;
  }
}

/// Every input the fuzzer ever crashed on (docs/fuzzing.md): refused or loaded, nothing else.
TEST(GltfMemory, FuzzerReproducersAreHandled) {
  const fs::path dir = fs::path(TRAY_SOURCE_DIR) / "fuzz" / "regressions";
  size_t count = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file()) continue;
    ++count;
    try {
      fromMemory(e.path());
    } catch (const Error& err) {
      EXPECT_EQ(std::string(err.what()).find('\n'), std::string::npos) << e.path();
    }
  }
  RecordProperty("reproducers", int(count));
}

}  // namespace
}  // namespace tray

#include "gltf/gltf_container.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <new>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "gltf/gltf_context.h"
#include "gltf/gltf_raw_fields.h"

namespace tray {

namespace {

uint32_t readU32(const unsigned char* p) {
  // GLB is little-endian (glTF 2.0 §4.4.2).
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

constexpr uint32_t kChunkJson = 0x4E4F534A, kChunkBin = 0x004E4942;

/// Deepest nesting of JSON arrays and objects, scanning until it passes `limit`. Parsers
/// (nlohmann's DOM, tinygltf's Value conversion of extras) recurse per level, so a file of a
/// million '[' would overflow the stack before any check could run.
size_t nestingDepth(std::string_view text, size_t limit) {
  size_t depth = 0, deepest = 0;
  bool inString = false, escaped = false;
  for (char c : text) {
    if (inString) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
      if (deepest > limit) break;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

constexpr size_t kMaxJsonDepth = 64;  // glTF itself needs about 6

}  // namespace

bool isGlb(const std::vector<unsigned char>& bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

std::string_view glbJson(const std::string& path, const std::vector<unsigned char>& bytes) {
  const uint64_t size = bytes.size();
  if (size < 20) failFile(path, "GLB file is truncated (shorter than its 20-byte header)");
  const unsigned char* b = bytes.data();
  if (readU32(b + 4) != 2)
    failFile(path,
             "GLB version " + std::to_string(readU32(b + 4)) + " is not supported (expected 2)");
  uint64_t length = readU32(b + 8);
  if (length != size)
    failFile(path, "GLB header states " + std::to_string(length) + " bytes but the file has " +
                       std::to_string(size));
  // Chunks: 8-byte header + data, each 4-byte aligned; all lengths in 64 bits, so no overflow.
  uint64_t jsonLength = readU32(b + 12);
  if (readU32(b + 16) != kChunkJson) failFile(path, "GLB's first chunk is not JSON");
  if (jsonLength == 0 || 20 + jsonLength > length)
    failFile(path,
             "GLB JSON chunk length " + std::to_string(jsonLength) + " does not fit in the file");
  if (jsonLength % 4 != 0) failFile(path, "GLB JSON chunk length is not a multiple of 4");
  uint64_t offset = 20 + jsonLength;
  if (offset < length) {
    if (offset + 8 > length) failFile(path, "GLB chunk header after the JSON chunk is truncated");
    uint64_t binLength = readU32(b + offset);
    if (readU32(b + offset + 4) != kChunkBin) failFile(path, "GLB's second chunk is not BIN");
    if (offset + 8 + binLength > length)
      failFile(path, "GLB BIN chunk length " + std::to_string(binLength) +
                         " runs past the end of the file");
    if (binLength % 4 != 0) failFile(path, "GLB BIN chunk length is not a multiple of 4");
  }
  return {reinterpret_cast<const char*>(b + 20), size_t(jsonLength)};
}

std::vector<unsigned char> withGlbJson(const std::vector<unsigned char>& bytes,
                                       std::string_view json) {
  const uint64_t oldJsonEnd = 20 + uint64_t(readU32(bytes.data() + 12));
  const uint64_t jsonLength = (json.size() + 3) / 4 * 4;
  const uint64_t total = 20 + jsonLength + (bytes.size() - oldJsonEnd);
  if (total > 0xffffffffu) throw Error("GLB with merged buffers exceeds 4 GiB");
  // Written in place into its final size (GCC 12 warns falsely about vector::insert after
  // reserve here, -Wstringop-overflow).
  std::vector<unsigned char> out(total, ' ');
  auto put32 = [&out](size_t at, uint64_t v) {
    for (int i = 0; i < 4; ++i) out[at + size_t(i)] = static_cast<unsigned char>(v >> (8 * i));
  };
  std::copy(bytes.begin(), bytes.begin() + 8, out.begin());  // magic, version
  put32(8, total);
  put32(12, jsonLength);
  put32(16, kChunkJson);
  std::copy(json.begin(), json.end(), out.begin() + 20);  // padded with spaces to jsonLength
  std::copy(bytes.begin() + std::ptrdiff_t(oldJsonEnd), bytes.end(),
            out.begin() + std::ptrdiff_t(20 + jsonLength));
  return out;
}

void checkJsonRoot(const std::string& path, std::string_view text) {
  if (text.empty()) failFile(path, "file is empty");
  if (nestingDepth(text, kMaxJsonDepth) > kMaxJsonDepth)
    failFile(path, "JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels");
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text.begin(), text.end());
  } catch (const std::bad_alloc&) {  // not a problem of the file: main reports it
    throw;
  } catch (const std::exception& e) {
    // nlohmann's messages start with "[json.exception.parse_error.101] ": keep the sentence.
    std::string what = e.what();
    size_t cut = what.find("] ");
    failFile(path, "invalid JSON: " + (cut == std::string::npos ? what : what.substr(cut + 2)));
  }
  if (!root.is_object()) failFile(path, "not a glTF file (the JSON root is not an object)");
  auto asset = root.find("asset");
  if (asset == root.end() || !asset->is_object())
    failFile(path, "not a glTF file (no 'asset' object)");
  auto version = asset->find("version");
  if (version == asset->end() || !version->is_string())
    failFile(path, "'asset' has no 'version' string");
  std::string v = version->get<std::string>();
  if (v.rfind("2.", 0) != 0) failFile(path, "glTF version '" + v + "' is not supported (2.x)");

  static const char* kCollections[] = {
      "accessors", "animations", "buffers",  "bufferViews", "cameras", "images",  "materials",
      "meshes",    "nodes",      "samplers", "scenes",      "skins",   "textures"};
  for (const char* key : kCollections) {
    auto it = root.find(key);
    if (it == root.end()) continue;
    if (!it->is_array()) failFile(path, std::string("'") + key + "' is not an array");
    for (size_t i = 0; i < it->size(); ++i)
      if (!(*it)[i].is_object())
        failFile(path, std::string(key) + "[" + std::to_string(i) + "] is not an object");
  }
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    auto it = root.find(key);
    if (it == root.end()) continue;
    if (!it->is_array()) failFile(path, std::string("'") + key + "' is not an array");
    for (const auto& e : *it)
      if (!e.is_string()) failFile(path, std::string("'") + key + "' holds a non-string");
  }
  auto scene = root.find("scene");
  if (scene != root.end() && !scene->is_number_unsigned())
    failFile(path, "'scene' is not a non-negative integer");
  checkRawFields(path, root);
}

}  // namespace tray

#include "gltf/scene_hash.h"

#include <xxhash.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/error.h"
#include "gltf/gltf_container.h"
#include "gltf/gltf_file_access.h"

namespace tray {
namespace {

using HashState = std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)>;

/// Adds the bytes of the file at `path` (streamed: scenes may be gigabytes); false if unreadable.
bool hashFile(XXH3_state_t* state, const std::string& path, std::vector<unsigned char>* keep) {
  std::unique_ptr<FILE, decltype(&std::fclose)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) return false;
  std::vector<unsigned char> chunk(1 << 20);
  size_t n;
  while ((n = std::fread(chunk.data(), 1, chunk.size(), f.get())) > 0) {
    XXH3_128bits_update(state, chunk.data(), n);
    if (keep) keep->insert(keep->end(), chunk.begin(), chunk.begin() + long(n));
  }
  return !std::ferror(f.get());
}

/// RFC 3986 §2.1 percent-decoding, as the loader applies to URIs before opening them.
std::string percentDecoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit((unsigned char)uri[i + 1]) &&
        std::isxdigit((unsigned char)uri[i + 2])) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

/// Every "uri" string of the document, depth first in document order.
void collectUris(const nlohmann::json& node, std::vector<std::string>& uris) {
  if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it)
      if (it.key() == "uri" && it->is_string())
        uris.push_back(it->get<std::string>());
      else
        collectUris(*it, uris);
  } else if (node.is_array()) {
    for (const auto& item : node) collectUris(item, uris);
  }
}

}  // namespace

std::string sceneContentHash(const std::string& scenePath, bool allowAnyPath,
                             const std::vector<std::string>& outsideFiles) {
  HashState state(XXH3_createState(), &XXH3_freeState);
  XXH3_128bits_reset(state.get());
  std::vector<unsigned char> bytes;
  if (!hashFile(state.get(), scenePath, &bytes))
    throw Error(scenePath + ": cannot read the scene file");
  std::vector<std::string> uris;
  try {  // a document that does not parse has no URIs here; the loader reports it
    const std::string json = isGlb(bytes) ? std::string(glbJson(scenePath, bytes))
                                          : std::string(bytes.begin(), bytes.end());
    collectUris(nlohmann::json::parse(json), uris);
  } catch (const std::exception&) {
  }
  bytes = {};
  const std::string folder = std::filesystem::path(scenePath).parent_path().string();
  const UriPolicy policy(folder.empty() ? "." : folder, allowAnyPath);
  for (const std::string& uri : uris) {
    XXH3_128bits_update(state.get(), uri.data(), uri.size() + 1);  // with its NUL: a separator
    if (uri.rfind("data:", 0) == 0) continue;  // inline: in the scene file's bytes already
    std::string problem;
    const std::string real = policy.resolve(percentDecoded(uri), problem);
    if (!real.empty()) hashFile(state.get(), real, nullptr);
  }
  for (const std::string& file : outsideFiles) {  // bytes only: mounts may differ by machine
    static const char kMarker[] = "\0outside\0";
    XXH3_128bits_update(state.get(), kMarker, sizeof kMarker);
    if (!hashFile(state.get(), file, nullptr))
      XXH3_128bits_update(state.get(), file.data(), file.size());
  }
  const XXH128_hash_t h = XXH3_128bits_digest(state.get());
  char hex[33];
  std::snprintf(hex, sizeof hex, "%016llx%016llx", (unsigned long long)h.high64,
                (unsigned long long)h.low64);
  return hex;
}

}  // namespace tray

#include "gltf/gltf_buffer_plan.h"

#include <map>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

namespace tray {

namespace {

uint64_t byteLengthOf(const nlohmann::json& buffer) {
  auto it = buffer.find("byteLength");
  if (it == buffer.end() || !it->is_number()) return 0;
  const double v = it->get<double>();  // validation refuses bad values later
  return v > 0 && v < 1.8e19 ? uint64_t(v) : 0;
}

}  // namespace

BufferPlan planBuffers(std::string_view text, const UriPolicy& policy) {
  BufferPlan plan;
  nlohmann::json root = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (!root.is_object() || !root.contains("buffers") || !root["buffers"].is_array()) return plan;
  nlohmann::json& buffers = root["buffers"];
  std::map<std::pair<std::string, uint64_t>, size_t> first;  // (real path, length) -> index
  std::vector<long> target(buffers.size(), -1);
  for (size_t i = 0; i < buffers.size(); ++i) {
    const nlohmann::json& b = buffers[i];
    if (!b.is_object()) continue;
    const uint64_t length = byteLengthOf(b);
    auto uri = b.find("uri");
    if (uri == b.end() || !uri->is_string() || !policy.allowsFiles()) {
      plan.bytes += length;
      continue;
    }
    const std::string u = uri->get<std::string>();
    std::string problem, real;
    if (u.rfind("data:", 0) != 0 && u.find('%') == std::string::npos)
      real = policy.resolve(u, problem);
    if (real.empty()) {
      plan.bytes += length;
      continue;
    }
    auto [it, added] = first.emplace(std::make_pair(real, length), i);
    if (added) {
      plan.bytes += length;
    } else {
      target[i] = long(it->second);
      plan.mergedBytes += length;
      ++plan.merged;
    }
  }
  if (plan.merged == 0) return plan;
  if (root.contains("bufferViews") && root["bufferViews"].is_array())
    for (nlohmann::json& view : root["bufferViews"]) {
      if (!view.is_object() || !view.contains("buffer") || !view["buffer"].is_number_unsigned())
        continue;
      const uint64_t b = view["buffer"].get<uint64_t>();
      if (b < target.size() && target[b] >= 0) view["buffer"] = target[b];
    }
  for (size_t i = 0; i < buffers.size(); ++i)
    if (target[i] >= 0) {
      buffers[i]["uri"] = "data:application/octet-stream;base64,AA==";
      buffers[i]["byteLength"] = 1;
    }
  plan.json = root.dump();
  return plan;
}

}  // namespace tray

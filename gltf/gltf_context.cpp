#include "gltf/gltf_context.h"

#include "core/error.h"

namespace tray {

std::string oneLine(const std::string& text) {
  constexpr size_t kMaxLength = 300;
  std::string out;
  bool pendingBreak = false;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      pendingBreak = true;
      continue;
    }
    if (pendingBreak && !out.empty()) out += "; ";
    pendingBreak = false;
    // Control characters from a hostile file must not reach a terminal.
    out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  if (out.size() > kMaxLength) out = out.substr(0, kMaxLength - 3) + "...";
  return out;
}

int findByNameOrIndex(const std::vector<std::string>& names, const std::string& which) {
  for (size_t i = 0; i < names.size(); ++i)
    if (names[i] == which) return int(i);
  if (!which.empty() && which.size() < 9 &&
      which.find_first_not_of("0123456789") == std::string::npos) {
    const size_t i = std::stoul(which);
    if (i < names.size()) return int(i);
  }
  return -1;
}

std::string listOfChoices(const std::vector<std::string>& names) {
  std::string list;
  for (size_t i = 0; i < names.size(); ++i) {
    list += i ? ", " : ": ";
    list += std::to_string(i);
    if (!names[i].empty()) list += " '" + names[i] + "'";
  }
  return list;
}

std::string nameOf(const char* kind, int index, const std::string& name) {
  std::string s = std::string(kind) + " " + std::to_string(index);
  if (!name.empty()) s += " '" + name + "'";
  return s;
}

void failFile(const std::string& path, const std::string& problem) {
  throw Error(oneLine(path + ": " + problem));
}

void GltfContext::fail(const std::string& problem) const {
  failFile(path, problem);
}

void GltfContext::warn(const std::string& message) const {
  if (report) report->warnings.push_back(oneLine(path + ": " + message));
}

}  // namespace tray

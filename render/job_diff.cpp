#include "render/job_diff.h"

#include <sstream>

namespace tray {

std::vector<std::pair<std::string, std::string>> jobFields(const std::string& job) {
  std::vector<std::pair<std::string, std::string>> fields;
  std::istringstream words(job);
  std::string word;
  while (words >> word) {
    const size_t eq = word.find('=');
    if (eq == std::string::npos || eq == 0) {
      if (fields.empty()) fields.emplace_back("", "");
      fields.back().second += " " + word;
    } else {
      fields.emplace_back(word.substr(0, eq), word.substr(eq + 1));
    }
  }
  return fields;
}

std::string jobDifference(const std::string& here, const std::string& there) {
  if (here == there) return "";
  const auto a = jobFields(here), b = jobFields(there);
  auto find = [](const auto& fields, const std::string& name) -> const std::string* {
    for (const auto& [n, v] : fields)
      if (n == name) return &v;
    return nullptr;
  };
  for (const auto& [name, value] : a) {
    const std::string* other = find(b, name);
    if (!other) return "the field '" + name + "' is missing there";
    if (*other != value) return name + " is '" + *other + "' there, '" + value + "' here";
  }
  for (const auto& [name, value] : b)
    if (!find(a, name)) return "the field '" + name + "' is missing here";
  return "the fields are in another order";
}

}  // namespace tray

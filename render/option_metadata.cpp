#include "render/option_metadata.h"

#include <cctype>
#include <string>

#include "integrators/registry.h"

namespace tray {
namespace {

/// "pixel-sampler" -> "pixelSampler": the attribute names EXR readers already know.
std::string camelCase(const std::string& name) {
  std::string out;
  bool upper = false;
  for (char c : name) {
    if (c == '-') {
      upper = true;
      continue;
    }
    out += upper ? char(std::toupper(static_cast<unsigned char>(c))) : c;
    upper = false;
  }
  return out;
}

}  // namespace

void addOptionMetadata(const RenderSettings& settings, ImageOutputOptions& out) {
  const RenderSettings bound = withIntegratorOptions(settings);
  for (const OptionSpec& spec : bound.declared()) {
    if (!spec.affectsPixels) continue;
    const std::string key = "tray:" + camelCase(spec.name);
    if (spec.name == "spp")
      out.floatMetadata.emplace_back(key, float(bound.getInt("spp")));
    else
      out.stringMetadata.emplace_back(key, formatOptionValue(bound.value(spec.name)));
  }
}

}  // namespace tray

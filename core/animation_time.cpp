#include "core/animation_time.h"

#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace tray {

const std::vector<OptionSpec>& animationOptions() {
  static const std::vector<OptionSpec> specs = {
      // Text, not float: "static" (no animation applied) differs from time 0, where animated
      // values replace the nodes' own, and the signature must tell them apart.
      choiceOption("time", "static", {},
                   "animation time in seconds; 'static': the nodes' own pose, no animation"),
      floatOption("fps", 24, 1e-3f, 1e6f, "frames per second: --frames N renders time N / fps"),
      choiceOption("animation", "all", {},
                   "glTF animation played at --time: all (together), an index or a name"),
  };
  return specs;
}

std::vector<OptionSpec> withAnimationOptions(std::vector<OptionSpec> specs) {
  const auto& animation = animationOptions();
  specs.insert(specs.end(), animation.begin(), animation.end());
  return specs;
}

std::optional<float> animationTime(const OptionValues& values) {
  const std::string text = values.getString("time");
  if (text == "static") return std::nullopt;
  char* end = nullptr;
  const float t = std::strtof(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(t))
    throw Error("--time " + text + ": expected seconds (a finite number) or 'static'");
  return t;
}

std::string frameTime(int64_t frame, float fps) {
  return formatOptionValue(OptionValue(float(double(frame) / double(fps))));
}

}  // namespace tray

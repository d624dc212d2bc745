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
      choiceOption("animation", "first", {},
                   "glTF animation played at --time: first (as glTF viewers play it), all "
                   "(together), an index or a name"),
      // Frames, not seconds: what a shutter angle means whatever the frame rate (180 degrees =
      // half a frame), as Arnold and Cycles count it. Text: "off" and a pair.
      choiceOption("shutter", "off", {},
                   "motion blur: OPEN,CLOSE in frames relative to the frame's time, e.g. "
                   "-0.25,0.25 (180-degree shutter centred on the frame); 'off': none"),
      intOption("motion-steps", 3, 2, 129,
                "motion blur: times the animation is evaluated at over the shutter (linear in "
                "between)"),
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

std::optional<Shutter> shutterOf(const OptionValues& values) {
  const std::string text = values.getString("shutter");
  if (text == "off") return std::nullopt;
  const std::string usage = "--shutter " + text +
                            ": expected OPEN,CLOSE in frames around the frame's time "
                            "(e.g. -0.25,0.25) or 'off'";
  const size_t comma = text.find(',');
  if (comma == std::string::npos) throw Error(usage);
  auto number = [&](const std::string& part) {
    char* end = nullptr;
    const float v = std::strtof(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !std::isfinite(v)) throw Error(usage);
    return v;
  };
  Shutter s{number(text.substr(0, comma)), number(text.substr(comma + 1))};
  if (!(s.close > s.open))
    throw Error("--shutter " + text + ": the shutter must close after it opens (CLOSE > OPEN)");
  return s;
}

std::string frameTime(int64_t frame, float fps) {
  return formatOptionValue(OptionValue(float(double(frame) / double(fps))));
}

}  // namespace tray

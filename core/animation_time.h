#pragma once
// The animation options of a render (docs/options.md): --time, --fps and --animation change the
// pixels of an animated scene, so they are render-wide options and reach the farm job signature
// and the EXR metadata (tray:time, tray:fps, tray:animation).
#include <optional>
#include <string>
#include <vector>

#include "core/options.h"

namespace tray {

/// --time (seconds, or "static": the file's unanimated pose), --fps (frames per second, for
/// --frames), --animation (all, an index or a name).
const std::vector<OptionSpec>& animationOptions();

/// `specs` followed by animationOptions(): the render-wide table (core/render_options.cpp).
std::vector<OptionSpec> withAnimationOptions(std::vector<OptionSpec> specs);

/// The time --time asks for; empty for "static". Throws tray::Error "--time TEXT: expected ..."
/// for anything but "static" or a finite number.
std::optional<float> animationTime(const OptionValues& values);

/// The --time text of frame `frame` at `fps` frames per second: frame / fps, in the fewest
/// digits that read back as the same float.
std::string frameTime(int64_t frame, float fps);

}  // namespace tray

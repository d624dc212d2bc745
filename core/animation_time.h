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
/// --frames), --animation (all, an index or a name), --shutter and --motion-steps (motion blur).
const std::vector<OptionSpec>& animationOptions();

/// `specs` followed by animationOptions(): the render-wide table (core/render_options.cpp).
std::vector<OptionSpec> withAnimationOptions(std::vector<OptionSpec> specs);

/// The time --time asks for; empty for "static". Throws tray::Error "--time TEXT: expected ..."
/// for anything but "static" or a finite number.
std::optional<float> animationTime(const OptionValues& values);

/// Motion blur's shutter interval, in frames relative to the frame's time (--time, or
/// frame / fps with --frames), as Arnold's shutter_start / shutter_end and Cycles' shutter
/// length in frames: -0.25,0.25 is a 180-degree shutter centred on the frame, 0,0.5 one that
/// opens on it.
struct Shutter {
  float open = 0, close = 0;
  /// The time in seconds of shutter fraction u (0: open, 1: close) around `time`.
  float at(float time, float fps, float u) const {
    return time + (open + u * (close - open)) / fps;
  }
};

/// --shutter: empty for "off". Throws tray::Error with one line for text that is not two
/// finite numbers OPEN,CLOSE or a close that does not come after open.
std::optional<Shutter> shutterOf(const OptionValues& values);

/// The --time text of frame `frame` at `fps` frames per second: frame / fps, in the fewest
/// digits that read back as the same float.
std::string frameTime(int64_t frame, float fps);

}  // namespace tray

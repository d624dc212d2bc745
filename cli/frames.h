#pragma once
// --frames A-B: an animation rendered frame by frame, each to outputs named by a pattern in -o
// ("out.####.exr" or "out.%04d.exr": the frame number, zero padded).
#include <cstdint>
#include <string>
#include <vector>

namespace tray {

struct FrameRange {
  int64_t first = 0, last = 0;
};

/// "A-B" (or "A": one frame) with 0 <= A <= B; throws tray::Error "--frames TEXT: expected ...".
FrameRange parseFrameRange(const std::string& text);

/// Whether `path` holds a frame pattern: a run of '#' or a printf "%d" / "%0Nd".
bool hasFramePattern(const std::string& path);

/// `path` with its (first) frame pattern replaced by `frame`, zero padded to the pattern's
/// width (the number of '#', or N of "%0Nd").
std::string framePath(const std::string& path, int64_t frame);

/// Throws tray::Error unless the outputs suit the request: with --frames, every output needs a
/// pattern (else every frame would overwrite one file); without, no output may have one.
void checkFramePatterns(const std::vector<std::string>& outputs, bool frames);

}  // namespace tray

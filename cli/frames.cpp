#include "cli/frames.h"

#include <cctype>
#include <cstdio>
#include <regex>

#include "core/error.h"

namespace tray {

namespace {

/// The frame pattern: a run of '#', or printf's %d with an optional zero-padded width.
const std::regex& patternRegex() {
  static const std::regex r("#+|%(0[0-9]{1,2})?d");
  return r;
}

bool parseCount(const std::string& text, int64_t& out) {
  if (text.empty() || text.size() > 9) return false;
  for (char c : text)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  out = std::stoll(text);
  return true;
}

}  // namespace

FrameRange parseFrameRange(const std::string& text) {
  const size_t dash = text.find('-');
  FrameRange r;
  const bool ok = dash == std::string::npos
                      ? parseCount(text, r.first) && (r.last = r.first, true)
                      : parseCount(text.substr(0, dash), r.first) &&
                            parseCount(text.substr(dash + 1), r.last);
  if (!ok || r.last < r.first)
    throw Error("--frames " + text + ": expected FIRST-LAST, two frame numbers >= 0 in order");
  return r;
}

bool hasFramePattern(const std::string& path) {
  return std::regex_search(path, patternRegex());
}

std::string framePath(const std::string& path, int64_t frame) {
  std::smatch m;
  if (!std::regex_search(path, m, patternRegex())) return path;
  const std::string token = m.str(0);
  const size_t width = token[0] == '#' ? token.size()
                                       : (m[1].matched ? std::stoul(m.str(1).substr(1)) : 1);
  std::string digits = std::to_string(frame);
  if (digits.size() < width) digits.insert(0, width - digits.size(), '0');
  return m.prefix().str() + digits + m.suffix().str();
}

void checkFramePatterns(const std::vector<std::string>& outputs, bool frames) {
  for (const auto& o : outputs) {
    if (frames && !hasFramePattern(o))
      throw Error("-o " + o + ": --frames needs a frame pattern in every output (out.####.exr or "
                  "out.%04d.exr), else each frame overwrites the last");
    if (!frames && hasFramePattern(o))
      throw Error("-o " + o + ": a frame pattern needs --frames FIRST-LAST");
  }
}

}  // namespace tray

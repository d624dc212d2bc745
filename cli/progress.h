#pragma once
// Render progress for people and for farm managers: a bar redrawn on a terminal, or plain lines
// that a log reader parses (--progress bar|plain|none).
#include <chrono>
#include <cstdio>
#include <string>

namespace tray {

enum class ProgressMode { kBar, kPlain, kNone };

/// "bar", "plain" or "none"; throws tray::Error (usage) for anything else.
ProgressMode parseProgressMode(const std::string& text);

struct ProgressSettings {
  ProgressMode mode = ProgressMode::kBar;
  double stepPercent = 10;      ///< plain: a line each time progress passes a multiple of this
  double intervalSeconds = 60;  ///< plain: and a line at least this often (0: never by time)
};

/// One plain progress line: "progress 42.0% elapsed 12.3 s eta 17.0 s" (no newline), the format
/// docs/farm.md documents for log parsers (Deadline's and OpenCue's progress regexes).
std::string plainProgressLine(double fraction, double elapsedSeconds);

/// Reports progress on `out` (stderr by default). The bar draws only when `out` is a terminal,
/// at most ten times a second; plain lines are written whatever `out` is, each flushed.
class Progress {
 public:
  explicit Progress(const ProgressSettings& settings = {}, FILE* out = stderr);
  void update(double fraction);
  /// Ends the bar's line, or writes the 100% line (once) in plain mode.
  void finish(bool complete = true);

 private:
  void drawBar(double fraction, double elapsed);
  ProgressSettings settings_;
  FILE* out_;
  bool barEnabled_;
  std::chrono::steady_clock::time_point start_, lastDraw_;
  double lastStep_ = 0;  ///< plain: the last multiple of stepPercent reported
  double lastFraction_ = -1;
};

}  // namespace tray

#include "cli/progress.h"

#include <unistd.h>

#include <cmath>

#include "core/error.h"

namespace tray {

ProgressMode parseProgressMode(const std::string& text) {
  if (text == "bar") return ProgressMode::kBar;
  if (text == "plain") return ProgressMode::kPlain;
  if (text == "none") return ProgressMode::kNone;
  throw Error("--progress " + text + ": expected bar, plain or none");
}

std::string plainProgressLine(double fraction, double elapsed) {
  char line[128];
  if (fraction > 0)
    std::snprintf(line, sizeof line, "progress %.1f%% elapsed %.1f s eta %.1f s", 100.0 * fraction,
                  elapsed, elapsed * (1.0 - fraction) / fraction);
  else
    std::snprintf(line, sizeof line, "progress %.1f%% elapsed %.1f s eta unknown", 0.0, elapsed);
  return line;
}

Progress::Progress(const ProgressSettings& settings, FILE* out)
    : settings_(settings),
      out_(out),
      barEnabled_(settings.mode == ProgressMode::kBar && isatty(fileno(out))),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

void Progress::update(double fraction) {
  if (settings_.mode == ProgressMode::kNone) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (settings_.mode == ProgressMode::kBar) {
    if (barEnabled_ && (fraction >= 1.0 || now - lastDraw_ >= std::chrono::milliseconds(100))) {
      lastDraw_ = now;
      drawBar(fraction, elapsed);
    }
    return;
  }
  // Plain: when a multiple of the step is passed, or the interval has gone by without a line.
  const double step = settings_.stepPercent > 0 ? settings_.stepPercent : 100.0;
  const double reached = std::floor(100.0 * fraction / step) * step;
  const bool byStep = reached > lastStep_;
  const bool byTime = settings_.intervalSeconds > 0 &&
                      std::chrono::duration<double>(now - lastDraw_).count() >=
                          settings_.intervalSeconds;
  if (!byStep && !byTime) return;
  lastStep_ = std::max(lastStep_, reached);
  lastDraw_ = now;
  lastFraction_ = fraction;
  std::fprintf(out_, "%s\n", plainProgressLine(fraction, elapsed).c_str());
  std::fflush(out_);
}

void Progress::finish(bool complete) {
  if (barEnabled_) std::fprintf(out_, "\r\033[K");
  if (settings_.mode == ProgressMode::kPlain && complete && lastFraction_ < 1.0) update(1.0);
}

void Progress::drawBar(double fraction, double elapsed) {
  const double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  constexpr int kWidth = 40;
  const int filled = int(fraction * kWidth);
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kWidth - filled), '.');
  std::fprintf(out_, "\r[%s] %5.1f%%  elapsed %.1fs  ETA %.1fs ", bar.c_str(), 100.0 * fraction,
               elapsed, eta);
  std::fflush(out_);
}

}  // namespace tray

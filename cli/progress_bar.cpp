#include "cli/progress_bar.h"

#include <unistd.h>

#include <string>

namespace tray {

ProgressBar::ProgressBar()
    : enabled_(isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()), lastDraw_() {}

void ProgressBar::update(double fraction) {
  if (!enabled_) return;
  auto now = std::chrono::steady_clock::now();
  if (fraction < 1.0 && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  double elapsed = std::chrono::duration<double>(now - start_).count();
  double eta = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  constexpr int kWidth = 40;
  int filled = int(fraction * kWidth);
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kWidth - filled), '.');
  std::fprintf(stderr, "\r[%s] %5.1f%%  elapsed %.1fs  ETA %.1fs ", bar.c_str(), 100.0 * fraction,
               elapsed, eta);
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_) std::fprintf(stderr, "\r\033[K");
}

}  // namespace tray

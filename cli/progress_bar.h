#pragma once
#include <chrono>
#include <cstdio>

namespace tray {

/// A one-line progress bar with ETA on stderr, drawn only when stderr is a terminal and at
/// most ten times a second.
class ProgressBar {
 public:
  ProgressBar();
  void update(double fraction);
  void finish();

 private:
  bool enabled_;
  std::chrono::steady_clock::time_point start_, lastDraw_;
};

}  // namespace tray

#pragma once
// When a render's next checkpoint is due (RenderOptions::checkpointSeconds): the one rule the
// tile renderer and the pass renderer (render/pass_renderer.h) share. Not thread-safe: both
// call it under their own lock.
#include <chrono>

#include "render/renderer.h"

namespace tray {

class CheckpointClock {
 public:
  using Clock = std::chrono::steady_clock;
  explicit CheckpointClock(const RenderOptions& options)
      : enabled_(options.onCheckpoint && options.checkpointSeconds > 0),
        seconds_(options.checkpointSeconds) {}
  void start(Clock::time_point now) { last_ = now; }
  /// True when a checkpoint is due now, no other is being written and the render goes on
  /// (`ending`: finished or stopped, when the final write follows anyway): the caller then
  /// writes it and calls release() after.
  bool claim(bool ending) {
    const auto now = Clock::now();
    if (!enabled_ || writing_ || ending ||
        std::chrono::duration<double>(now - last_).count() < seconds_)
      return false;
    writing_ = true;
    last_ = now;
    return true;
  }
  void release() { writing_ = false; }

 private:
  const bool enabled_;
  const double seconds_;
  bool writing_ = false;
  Clock::time_point last_;
};

}  // namespace tray

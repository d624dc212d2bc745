#pragma once
// How long a render took: wall seconds, which a user waits, and the process's CPU seconds
// (every thread's user + system time), which benchmarks compare across renderers without the
// scene loading and start-up before the render or the image writing after it (issue 37:
// subtracting a separately timed start-up left about +-20% noise on 128x128 renders).
#include <chrono>
#include <ctime>

namespace tray {

/// Seconds of one render, or of several added up (a resumed render, merged parts).
struct RenderTime {
  double seconds = 0;     ///< wall-clock
  double cpuSeconds = 0;  ///< the process's CPU time, all threads
  RenderTime operator+(const RenderTime& o) const {
    return {seconds + o.seconds, cpuSeconds + o.cpuSeconds};
  }
};

/// The process's CPU time so far (CLOCK_PROCESS_CPUTIME_ID: all threads, user + system).
inline double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

/// Started at construction (or restart()); elapsed() is the RenderTime since.
class RenderClock {
 public:
  using Clock = std::chrono::steady_clock;
  RenderClock() { restart(); }
  void restart() {
    wallStart_ = Clock::now();
    cpuStart_ = processCpuSeconds();
  }
  Clock::time_point started() const { return wallStart_; }
  RenderTime elapsed() const {
    return {std::chrono::duration<double>(Clock::now() - wallStart_).count(),
            processCpuSeconds() - cpuStart_};
  }

 private:
  Clock::time_point wallStart_;
  double cpuStart_ = 0;
};

}  // namespace tray

#pragma once
// CPU seconds of this process (user + system, every thread), the benchmarks' clock: figures per
// CPU-second stay comparable when other work shares the machine. The renderer's own clock
// (render/render_time.h), which tray:renderCpuSeconds reads.
#include "render/render_time.h"

inline double cpuSeconds() { return tray::processCpuSeconds(); }

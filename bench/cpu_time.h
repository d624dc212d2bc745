#pragma once
// CPU seconds of this process (user + system), the benchmarks' clock: figures per CPU-second
// stay comparable when other work shares the machine.
#include <sys/resource.h>

inline double cpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

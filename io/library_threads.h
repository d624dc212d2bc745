#pragma once
// Threads that libraries we never call start as they load, kept from costing anything.

namespace tray {

/// OpenImageIO 2.4 on Debian links OpenCV, which links OpenBLAS; OpenBLAS's constructor starts
/// one thread per core, and each spins on sched_yield for about 2^28 cycles (its
/// THREAD_TIMEOUT) before it sleeps. TRay never calls BLAS, yet that spin took 0.1 CPU s of
/// every tray-render on 2 cores (perf: sched_yield in libopenblas's thread; more cores, more
/// threads) and landed inside one-thread renders' CPU time.
///
/// This shuts OpenBLAS's threads down through its exported blas_thread_shutdown_ (OpenBLAS
/// starts them again if BLAS is ever called); with another BLAS, or none, it does nothing.
/// Call it first in main(): the spin from OpenBLAS's constructor to main() remains (about
/// 0.05 CPU s on 2 cores). Setting OPENBLAS_NUM_THREADS=1 from an ELF .preinit_array function
/// does not help: libc's own initialisation, which runs after it, resets the environment.
void stopIdleLibraryThreads();

}  // namespace tray

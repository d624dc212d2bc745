#include "io/library_threads.h"

#include <dlfcn.h>

namespace tray {

void stopIdleLibraryThreads() {
  // Looked up, not linked: TRay does not depend on OpenBLAS, only finds it loaded.
  using Shutdown = int (*)();
  if (void* symbol = dlsym(RTLD_DEFAULT, "blas_thread_shutdown_"))
    reinterpret_cast<Shutdown>(symbol)();
}

}  // namespace tray

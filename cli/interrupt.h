#pragma once
// SIGINT and SIGTERM for tray-render: a stop flag the render job polls, and the signal that set
// it for the exit code. The process's business, so the command line's, not the library's.
#include <atomic>

namespace tray {

/// Installs SIGINT and SIGTERM handlers that set the returned flag and remember the signal;
/// each restores the default action, so a second signal ends the process at once.
const std::atomic<bool>& installInterruptHandlers();
/// The first signal received (0: none); the exit code is 128 + it (130 SIGINT, 143 SIGTERM).
int interruptSignal();

}  // namespace tray

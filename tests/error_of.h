#pragma once
// What a call throws as tray::Error, for tests that check one-line messages.
#include <functional>
#include <string>

#include "core/error.h"

namespace tray {

/// The message of the tray::Error `f` throws; "(no error)" if it throws none.
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace tray

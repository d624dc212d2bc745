#pragma once
#include <stdexcept>
#include <string>

namespace tray {

/// The one error type that reaches the user: its message is a complete one-line sentence
/// (naming the file and the problem for input errors). Caught only in main().
class Error : public std::runtime_error {
 public:
  enum class Kind { kInput, kRender };
  explicit Error(const std::string& message, Kind kind = Kind::kInput)
      : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

}  // namespace tray

#pragma once
// The system failed us, not the input: a file or directory that cannot be written (the disk
// full, a path that cannot be made), memory the machine does not have. The command line exits
// with 3 on it and prints the OS's reason (InputError is the input's fault: exit 2).

#include <stdexcept>
#include <string>
#include <system_error>

namespace tsm::io {

class SystemError : public std::runtime_error {
 public:
  /// `what`: the path or the resource; `reason`: the OS's words (strerror), or what ran out.
  SystemError(const std::string& what, const std::string& reason) : std::runtime_error(what + ": " + reason) {}
};

/// The OS's words for an errno value ("No space left on device").
inline std::string os_reason(int error) { return std::error_code(error, std::generic_category()).message(); }

/// The memory a run needs and the machine does not have (io/memory_budget): Python's MemoryError.
class MemoryShortage : public SystemError {
 public:
  using SystemError::SystemError;
};

}  // namespace tsm::io

#pragma once
// The one exception of the library: bad input, with the JSON path of the offending value.
// (Non-convergence is never an exception: see solver::Status.)

#include <stdexcept>
#include <string>

namespace tsm::io {

class InputError : public std::runtime_error {
 public:
  InputError(std::string path, std::string reason)
      : std::runtime_error(path.empty() ? reason : path + ": " + reason),
        path_(std::move(path)),
        reason_(std::move(reason)) {}
  const std::string& path() const { return path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string path_;
  std::string reason_;
};

}  // namespace tsm::io

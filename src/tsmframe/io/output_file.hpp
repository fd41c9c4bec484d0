#pragma once
// One output file, written through a file descriptor so that a failure carries the OS's reason
// ("No space left on device", "File too large"): the run's outputs go into a fresh temporary
// directory (output_directory.hpp), which is what makes them appear whole or not at all.

#include <functional>
#include <ostream>
#include <string>

namespace tsm::io {

/// Creates (or truncates) `path`, writes it through `write`, syncs it to disk and closes it.
/// Throws SystemError (the path, the OS's reason) where the system fails; the partial file is
/// removed.
void write_output_file(const std::string& path, const std::function<void(std::ostream&)>& write);

/// Creates `directory` and its missing parents; throws SystemError with the OS's reason.
void make_directories(const std::string& directory);

}  // namespace tsm::io

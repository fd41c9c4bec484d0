#pragma once
// An input file's text — a model file or a study file — read whole, but never more than a JSON
// input can sanely be: a directory, a device that never ends (/dev/zero) or a file past
// max_input_bytes is refused with one reason before its text fills memory.

#include <string>

namespace tsm::io {

/// The largest input file read: 1 GiB of JSON parses into ~9 GiB of document (memory_estimate).
inline constexpr double max_input_bytes = 1024.0 * 1024.0 * 1024.0;

/// The whole text of the file at `path`. Throws InputError with an empty path and the reason: the
/// file cannot be opened or read ("cannot open " + `what`), is a directory, is larger than
/// max_input_bytes, or holds a NUL byte (no JSON text does; /dev/zero is refused at its first byte).
std::string read_input_file(const std::string& path, const std::string& what = "the file");

}  // namespace tsm::io

#include "tsmframe/io/input_file.hpp"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"

namespace tsm::io {
namespace {

[[noreturn]] void too_large() { fail("", "larger than 1 GiB, more than an input file may be (its parsed document would take ~10 GiB)"); }

}  // namespace

std::string read_input_file(const std::string& path, const std::string& what) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) fail("", "is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("", "cannot open " + what);
  std::string text;
  // A regular file's size is known before it is read; a device or a pipe is read up to the limit.
  if (const auto size = std::filesystem::file_size(path, error); !error) {
    if (static_cast<double>(size) > max_input_bytes) too_large();
    text.reserve(size);
  }
  std::vector<char> buffer(1 << 16);
  while (in.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) || in.gcount() > 0) {
    const size_t n = static_cast<size_t>(in.gcount());
    if (const void* nul = std::memchr(buffer.data(), '\0', n))
      fail("", "holds a NUL byte (byte " + std::to_string(text.size() + (static_cast<const char*>(nul) - buffer.data()) + 1) +
                   "): not JSON text");
    if (static_cast<double>(text.size() + n) > max_input_bytes) too_large();
    text.append(buffer.data(), n);
  }
  if (in.bad()) fail("", "cannot read " + what);
  return text;
}

}  // namespace tsm::io

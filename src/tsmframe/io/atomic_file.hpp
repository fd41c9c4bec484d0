#pragma once
// Files that appear whole or not at all: written beside their final name, flushed to disk,
// then renamed over it. A run killed half-way leaves the previous file (or none).

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace tsm::io {

/// One file to write: its final path and a function that writes its content.
struct PendingFile {
  std::string path;
  std::function<void(std::ostream&)> write;
};

/// Writes every file to a temporary beside it, syncs, then renames them into place.
/// Throws std::runtime_error (with the path) if anything fails; temporaries are removed.
void write_files_atomically(const std::vector<PendingFile>& files);

}  // namespace tsm::io

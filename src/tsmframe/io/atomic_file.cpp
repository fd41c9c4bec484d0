#include "tsmframe/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace tsm::io {
namespace {

void sync_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw std::runtime_error(path + ": cannot reopen to sync");
  const bool ok = ::fsync(fd) == 0;
  ::close(fd);
  if (!ok) throw std::runtime_error(path + ": cannot sync to disk");
}

}  // namespace

void write_files_atomically(const std::vector<PendingFile>& files) {
  std::vector<std::string> temporaries;
  try {
    for (const PendingFile& file : files) {
      const std::string temporary = file.path + ".tmp-" + std::to_string(::getpid());
      temporaries.push_back(temporary);
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw std::runtime_error(file.path + ": cannot create the file");
      file.write(out);
      out.flush();
      if (!out) throw std::runtime_error(file.path + ": cannot write the file");
      out.close();
      sync_file(temporary);
    }
    for (size_t k = 0; k < files.size(); ++k)
      if (std::rename(temporaries[k].c_str(), files[k].path.c_str()) != 0)
        throw std::runtime_error(files[k].path + ": cannot move the finished file into place");
  } catch (...) {
    for (const std::string& temporary : temporaries) std::remove(temporary.c_str());
    throw;
  }
}

}  // namespace tsm::io

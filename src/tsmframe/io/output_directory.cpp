#include "tsmframe/io/output_directory.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <system_error>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/system_error.hpp"

// What a kill leaves, at each moment of a run writing DIR:
// - before the temporary .DIR.tsmframe-HOST-PID exists, or while the run writes into it: DIR
//   untouched (the previous outputs, or none); the temporary is a dead run's, which the next run
//   writing beside it removes.
// - at the commit, renameat2(RENAME_EXCHANGE) swaps the two names in one step: before it DIR is
//   the previous outputs, after it the new ones; the temporary's name then holds the previous
//   outputs until they are removed (a kill meanwhile leaves them to the next run's clean-up).
//   Where DIR does not exist, one rename (RENAME_NOREPLACE) puts the new outputs there.
// - on a filesystem without RENAME_EXCHANGE (NFS), two renames: DIR moves aside to
//   .DIR.previous.tsmframe-HOST-PID, then the temporary becomes DIR. A kill between them leaves
//   no DIR; the next run's clean-up renames the previous outputs back to DIR.

namespace tsm::io {
namespace fs = std::filesystem;
namespace {

constexpr const char* marker = ".tsmframe-";
constexpr const char* previous_marker = ".previous";  ///< before `marker`: outputs moved aside

/// This host's name, as a temporary directory's name carries it (process ids are per host).
const std::string& host_name() {
  static const std::string name = [] {
    char buffer[256] = {};
    std::string host = ::gethostname(buffer, sizeof buffer - 1) == 0 && buffer[0] ? buffer : "localhost";
    for (char& c : host)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_')) c = '_';
    return host;
  }();
  return name;
}

/// Whether process `pid` runs: it exists and is no zombie (killed, not yet reaped by its parent).
bool process_alive(long pid) {
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;  // no /proc: as kill says
  const size_t name_end = line.rfind(')');  // "pid (name) state …", the name may hold anything
  return !(name_end != std::string::npos && name_end + 2 < line.size() && line[name_end + 2] == 'Z');
}

/// The entries of the existing directory `final` that the command does not write there (a
/// previous version's `results.json.tmp-PID` leftovers aside).
std::vector<std::string> foreign_entries(const fs::path& final, const std::vector<std::string>& own) {
  std::vector<std::string> foreign;
  std::error_code error;
  for (fs::directory_iterator it(final, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    const bool ours = std::any_of(own.begin(), own.end(), [&](const std::string& o) {
      if (name == o) return true;
      const std::string leftover = o + ".tmp-";
      return name.size() > leftover.size() && name.compare(0, leftover.size(), leftover) == 0 &&
             name.find_first_not_of("0123456789", leftover.size()) == std::string::npos;
    });
    if (!ours) foreign.push_back(name);
  }
  if (error) throw SystemError(final.string(), error.message());
  std::sort(foreign.begin(), foreign.end());
  return foreign;
}

/// Whether `directory` is where a filesystem is mounted (a bind mount of a container included):
/// no rename can move it.
bool mount_root(const fs::path& directory) {
#ifdef STATX_ATTR_MOUNT_ROOT
  struct statx x;
  if (::statx(AT_FDCWD, directory.c_str(), AT_SYMLINK_NOFOLLOW, 0, &x) == 0 && (x.stx_attributes_mask & STATX_ATTR_MOUNT_ROOT))
    return (x.stx_attributes & STATX_ATTR_MOUNT_ROOT) != 0;
#endif
  struct stat self, parent;
  return ::stat(directory.c_str(), &self) == 0 && ::stat(directory.parent_path().c_str(), &parent) == 0 &&
         self.st_dev != parent.st_dev;
}

/// Refuses an existing `final` that the commit may not replace: not a directory, or holding
/// what the command does not write (`shown`: the directory as the user named it).
void check_replaceable(const fs::path& final, const std::string& shown, const std::vector<std::string>& own) {
  struct stat status;
  if (::lstat(final.c_str(), &status) != 0) {
    if (errno == ENOENT) return;
    throw SystemError(shown, os_reason(errno));
  }
  if (!S_ISDIR(status.st_mode)) throw InputError(shown, "exists and is not a directory: the outputs need a directory of their own");
  if (mount_root(final))
    throw InputError(shown, "is a mount point, which the outputs cannot replace whole: give a directory inside it");
  const std::vector<std::string> foreign = foreign_entries(final, own);
  if (foreign.empty()) return;
  std::string names;
  for (size_t k = 0; k < foreign.size() && k < 3; ++k) names += (k ? ", " : "") + foreign[k];
  if (foreign.size() > 3) names += " and " + std::to_string(foreign.size() - 3) + " more";
  throw InputError(shown, "holds " + names +
                              ", which tsmframe does not write there; the outputs replace the directory whole: "
                              "choose another output directory, or move them");
}

/// Makes the missing directories of `parent`, outermost first; returns those it made.
std::vector<fs::path> make_parents(const fs::path& parent) {
  std::vector<fs::path> chain;
  for (fs::path p = parent; !p.empty() && p != p.root_path(); p = p.parent_path()) chain.push_back(p);
  std::vector<fs::path> made;
  for (auto p = chain.rbegin(); p != chain.rend(); ++p) {
    if (::mkdir(p->c_str(), 0777) == 0) made.push_back(*p);
    else if (errno != EEXIST) {
      for (auto q = made.rbegin(); q != made.rend(); ++q) ::rmdir(q->c_str());
      throw SystemError(p->string(), os_reason(errno));
    }
  }
  return made;
}

/// `directory` as a final output directory: absolute, without symbolic links where it exists,
/// its name last ("out/" where out does not exist yet: "out").
fs::path final_path(const std::string& directory) {
  std::error_code error;
  fs::path final = fs::weakly_canonical(fs::absolute(directory, error), error);
  if (error) throw SystemError(directory, error.message());
  if (!final.has_filename()) final = final.parent_path();
  return final;
}

/// Whether `entry` (a name beside an output directory) is the temporary of a dead run on this host.
bool dead_temporary(const std::string& entry) {
  const long owner = temporary_owner(entry);
  return owner >= 0 && !(owner != ::getpid() && process_alive(owner));
}

/// Removes the temporaries beside `final` of dead runs on this host (but `keep`); outputs a dead run had moved
/// aside go back to their place where it is empty (a kill between the two renames).
void remove_dead_temporaries(const fs::path& parent, const fs::path& keep) {
  std::error_code error;
  for (fs::directory_iterator it(parent, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (!dead_temporary(name) || it->path() == keep) continue;
    const size_t aside = name.rfind(std::string(previous_marker) + marker);
    std::error_code ignored;
    if (aside != std::string::npos && ::rename(it->path().c_str(), (parent / name.substr(1, aside - 1)).c_str()) == 0)
      continue;
    fs::remove_all(it->path(), ignored);
  }
}

void sync_path(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw SystemError(path.string(), os_reason(errno));
  const int error = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  if (error != 0 && error != EINVAL) throw SystemError(path.string(), os_reason(error));  // EINVAL: cannot be synced
}

/// Every file and directory under `directory` and itself on the disk (what another program wrote
/// there too: the plots).
void sync_tree(const fs::path& directory) {
  std::error_code error;
  for (fs::recursive_directory_iterator it(directory, error), end; !error && it != end; it.increment(error))
    if (it->is_regular_file() || it->is_directory()) sync_path(it->path());
  if (error) throw SystemError(directory.string(), error.message());
  sync_path(directory);
}

/// Moves `final` aside, then `temporary` to `final` (a filesystem without RENAME_EXCHANGE);
/// returns where the previous outputs are.
fs::path rename_twice(const fs::path& temporary, const fs::path& final) {
  const fs::path aside = final.parent_path() / temporary_name(final.filename().string() + previous_marker, ::getpid());
  if (::rename(final.c_str(), aside.c_str()) != 0) throw SystemError(final.string(), os_reason(errno));
  if (::rename(temporary.c_str(), final.c_str()) == 0) return aside;
  const int failure = errno;
  ::rename(aside.c_str(), final.c_str());
  throw SystemError(final.string(), os_reason(failure));
}

/// Puts `temporary` in place of `final` in one step: exchanged with an existing `final`, renamed
/// where there is none. Returns where the previous outputs now are (empty: there were none).
fs::path put_in_place(const fs::path& temporary, const fs::path& final) {
  // `final` may appear or vanish meanwhile (another run writing it): a few tries.
  for (int attempt = 0; attempt < 8; ++attempt) {
    if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, final.c_str(), RENAME_EXCHANGE) == 0) return temporary;
    if (errno == EINVAL || errno == ENOSYS) return rename_twice(temporary, final);
    if (errno != ENOENT || !fs::exists(temporary)) throw SystemError(final.string(), os_reason(errno));
    if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, final.c_str(), RENAME_NOREPLACE) == 0) return {};
    if (errno == EINVAL || errno == ENOSYS) {
      if (::rename(temporary.c_str(), final.c_str()) == 0) return {};
    }
    if (errno != EEXIST && errno != ENOTEMPTY) throw SystemError(final.string(), os_reason(errno));
  }
  throw SystemError(final.string(), "another process keeps replacing it");
}

}  // namespace

std::string temporary_name(const std::string& name, long pid) {
  return "." + name + marker + host_name() + "-" + std::to_string(pid);
}

long temporary_owner(const std::string& entry) {
  const size_t at = entry.rfind(marker);
  if (entry.empty() || entry[0] != '.' || at == std::string::npos || at == 0) return -1;
  const std::string owner = entry.substr(at + std::char_traits<char>::length(marker));
  const std::string prefix = host_name() + "-";
  if (owner.compare(0, prefix.size(), prefix) != 0) return -1;
  const std::string digits = owner.substr(prefix.size());
  if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return -1;
  return std::stol(digits);
}

std::vector<fs::path> dead_temporaries(const std::string& directory) {
  const fs::path final = final_path(directory);
  std::string prefix = ".";  // (appended, not concatenated: g++ 12 warns falsely of overlapping copies)
  prefix += final.filename().string();
  prefix += marker;
  std::vector<std::pair<fs::file_time_type, fs::path>> found;
  std::error_code error;
  for (fs::directory_iterator it(final.parent_path(), error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    std::error_code ignored;
    if (name.compare(0, prefix.size(), prefix) == 0 && dead_temporary(name) && it->is_directory(ignored))
      found.emplace_back(fs::last_write_time(it->path(), ignored), it->path());
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<fs::path> paths;
  for (auto& [time, path] : found) paths.push_back(std::move(path));
  return paths;
}

OutputDirectory::OutputDirectory(const std::string& directory, const std::vector<std::string>& own, const fs::path& adopt) {
  std::error_code error;
  final_ = final_path(directory);
  const fs::path working = fs::current_path(error);
  const auto [inside, rest] = std::mismatch(final_.begin(), final_.end(), working.begin(), working.end());
  if (final_ == final_.root_path() || (!error && inside == final_.end()))
    throw InputError(directory, "is (or holds) the working directory, which the outputs cannot replace whole: give another directory");
  check_replaceable(final_, directory, own);
  const fs::path parent = final_.parent_path();
  made_parents_ = make_parents(parent);
  temporary_ = parent / temporary_name(final_.filename().string(), ::getpid());
  const bool adopted = !adopt.empty() && adopt.parent_path() == parent && dead_temporary(adopt.filename().string()) &&
                       ::rename(adopt.c_str(), temporary_.c_str()) == 0;
  remove_dead_temporaries(parent, adopted ? temporary_ : fs::path());
  if (!adopted && ::mkdir(temporary_.c_str(), 0777) != 0) {
    const int failure = errno;
    for (auto p = made_parents_.rbegin(); p != made_parents_.rend(); ++p) ::rmdir(p->c_str());
    throw SystemError(directory, "cannot make its temporary directory " + temporary_.string() + ": " + os_reason(failure));
  }
}

OutputDirectory::~OutputDirectory() {
  std::error_code ignored;
  if (!committed_) {
    fs::remove_all(temporary_, ignored);
    for (auto p = made_parents_.rbegin(); p != made_parents_.rend(); ++p) ::rmdir(p->c_str());  // where empty
  }
}

void OutputDirectory::commit() {
  sync_tree(temporary_);
  struct stat previous;
  if (::stat(final_.c_str(), &previous) == 0 && S_ISDIR(previous.st_mode))
    ::chmod(temporary_.c_str(), previous.st_mode & 07777);  // the directory keeps its permissions
  const fs::path old = put_in_place(temporary_, final_);
  committed_ = true;
  std::error_code ignored;
  if (!old.empty()) fs::remove_all(old, ignored);  // a kill meanwhile: the next run's clean-up
  const int fd = ::open(final_.parent_path().c_str(), O_RDONLY | O_CLOEXEC);  // the rename on the disk, where it can be
  if (fd >= 0) ::fsync(fd), ::close(fd);
}

}  // namespace tsm::io

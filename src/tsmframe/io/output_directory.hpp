#pragma once
// A run's output directory, committed whole: the run writes every output (results.json,
// steps.csv, vtk/, plots/; a study's rows and cases/) into a fresh temporary directory beside
// the final one, then puts it in place of the final one in one step. A run killed at any moment
// leaves the previous outputs or the new ones, never a mix; a later run removes the temporaries
// of runs that died. The temporary's name says it is tsmframe's and whose it is:
// `.<name>.tsmframe-<host>-<pid>` beside `<name>`.

#include <filesystem>
#include <string>
#include <vector>

namespace tsm::io {

class OutputDirectory {
 public:
  /// Prepares to write `directory`: makes its missing parents and the temporary directory, and
  /// removes the temporaries of dead runs beside it (never a live run's). An existing
  /// `directory` must be a directory holding nothing but `own` entries (what the command writes
  /// there), and no mount point: the commit replaces it whole, and anything else in it would be
  /// lost. Throws
  /// SystemError (the OS's reason) where the directory cannot be made, InputError (path: the
  /// directory) where an existing one may not be replaced.
  /// `adopt`: a dead run's temporary directory beside `directory` (dead_temporaries) to go on
  /// from: it becomes this run's temporary, with what it holds, in one rename.
  OutputDirectory(const std::string& directory, const std::vector<std::string>& own, const std::filesystem::path& adopt = {});
  /// Removes the temporary directory (and the parents it made) unless committed.
  ~OutputDirectory();
  OutputDirectory(const OutputDirectory&) = delete;
  OutputDirectory& operator=(const OutputDirectory&) = delete;

  /// Where the outputs are written until the commit.
  const std::filesystem::path& path() const { return temporary_; }
  /// Syncs the temporary directory to disk and puts it in place of the final one; the previous
  /// outputs are removed. Throws SystemError where the system refuses.
  void commit();

 private:
  std::filesystem::path final_, temporary_;
  std::vector<std::filesystem::path> made_parents_;  ///< parents this run created, outermost first
  bool committed_ = false;
};

/// The temporary directories beside `directory` of dead runs on this host, the newest first:
/// what they hold is what those runs had written when they died.
std::vector<std::filesystem::path> dead_temporaries(const std::string& directory);

/// The name of the temporary directory a run with process id `pid` on this host writes `name`'s
/// outputs into.
std::string temporary_name(const std::string& name, long pid);
/// The process id of a temporary directory (or leftover) named `entry` made on this host; −1 if
/// `entry` is no tsmframe temporary of this host.
long temporary_owner(const std::string& entry);

}  // namespace tsm::io

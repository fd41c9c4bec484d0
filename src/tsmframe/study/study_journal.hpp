#pragma once
// A study's journal: `study.rows.jsonl` in its output directory, written as the cases end — a
// header line naming the study by its fingerprint, then one line per finished case, its row as
// JSON. A study killed at any moment (SIGKILL, a lost machine, a batch job's time limit) keeps
// the rows of its finished cases there: in its output directory where it stopped on a signal
// and wrote its outputs, else in the temporary directory it was writing (io/output_directory.hpp)
// beside it. `tsmframe study --resume` finds them and runs only the other cases. A line cut short
// by the kill is not a row: that case runs again.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tsmframe/study/study.hpp"
#include "tsmframe/study/study_runner.hpp"

namespace tsm::study {

inline constexpr const char* journal_name = "study.rows.jsonl";

/// One row as a journal line holds it (every field of CaseResult; a number that is not finite as null).
nlohmann::json row_json(const CaseResult& row);
/// The journal's lines for `rows` (each ended by a newline), as a journal appends them: what a
/// shard run elsewhere sends back to be appended to a journal of the study (a Dask task's).
std::string journal_lines(const std::vector<CaseResult>& rows);
/// The row a journal line holds, for `study`; nothing where the line is not one of its rows (a
/// case number out of range, a field missing or of the wrong type).
std::optional<CaseResult> row_from_json(const nlohmann::json& line, const Study& study);

/// The finished cases' rows a journal holds, by case (the first row of a case where it holds two).
struct JournalRows {
  std::vector<CaseResult> rows;
  size_t skipped = 0;  ///< lines that are not rows of the study (a line cut short by a kill)
};

/// Reads the journal at `path`. Throws io::InputError (the path) where its header names another
/// study (the study file, its model or tsmframe changed since it ran) or is no journal's; a
/// file that cannot be read is io::SystemError.
JournalRows read_journal(const std::filesystem::path& path, const Study& study);

/// Where a study writing `out` may go on from: the journal in the temporary directory of a run
/// that died (this host's, the newest first), else in `out` itself.
struct ResumePoint {
  std::filesystem::path directory;  ///< holding the journal
  bool temporary = false;           ///< a dead run's temporary directory (io::OutputDirectory adopts it)
  JournalRows journal;
};

/// The newest journal of `study` beside or in `out` (ResumePoint); nothing where there is none.
/// Throws io::InputError where the newest journal there is another study's.
std::optional<ResumePoint> find_resume_point(const std::string& out, const Study& study);

/// Appends rows to a new journal: its header and the rows given (those a resumed study already
/// has), then each row as its case ends. A row reaches the file when append returns (a kill of
/// the process loses none) and the disk within a second (fdatasync, at most once a second).
class StudyJournal {
 public:
  /// Writes the journal at `path` anew (over a file there, in one rename). Throws
  /// io::SystemError where the system refuses.
  StudyJournal(const std::filesystem::path& path, const Study& study, const std::vector<CaseResult>& rows);
  ~StudyJournal();
  StudyJournal(const StudyJournal&) = delete;
  StudyJournal& operator=(const StudyJournal&) = delete;

  /// Appends a finished case's row (a case stopped on request, status "interrupted", is not
  /// finished: it is left out). Throws io::SystemError where the system refuses.
  void append(const CaseResult& row);

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::int64_t last_sync_ = 0;  ///< steady clock, ms
};

}  // namespace tsm::study

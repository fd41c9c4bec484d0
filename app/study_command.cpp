#include "study_command.hpp"

#include <omp.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>

#include "exit_codes.hpp"
#include "progress.hpp"
#include "python_script.hpp"
#include "stop_signals.hpp"
#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/output_directory.hpp"
#include "tsmframe/io/system_error.hpp"
#include "tsmframe/study/study_journal.hpp"
#include "tsmframe/study/study_runner.hpp"
#include "tsmframe/study/study_writer.hpp"

namespace tsm::app {
namespace {

/// `--shard I/N` (1 ≤ I ≤ N ≤ a million); throws io::InputError otherwise.
tsm::study::StudyShard parse_shard(const std::string& text) {
  const size_t slash = text.find('/');
  size_t i = 0, n = 0;
  const auto whole = [](const std::string& digits, size_t& value) {
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    return !digits.empty() && error == std::errc() && end == digits.data() + digits.size();
  };
  if (slash == std::string::npos || !whole(text.substr(0, slash), i) || !whole(text.substr(slash + 1), n) || i < 1 || i > n ||
      n > tsm::study::max_cases)
    throw tsm::io::InputError("--shard", "expected I/N, this run's share I of N (1 <= I <= N <= 1000000), got \"" + text + "\"");
  return {i - 1, n};
}

/// Where the study goes on from with --resume (nothing: from the start); without it, a note
/// where an unfinished run's rows are about to be replaced. Throws io::InputError where the
/// journal there is another study's (with --resume only).
std::optional<tsm::study::ResumePoint> resume_point(const StudyOptions& options, const tsm::study::Study& definition) {
  std::optional<tsm::study::ResumePoint> point;
  try {
    point = tsm::study::find_resume_point(options.out, definition);
  } catch (const tsm::io::InputError& e) {
    if (options.resume) throw tsm::io::InputError("--resume", std::string(e.what()) + ": run without --resume to start over");
    return std::nullopt;  // another study's rows: replaced, as any output is
  }
  if (!point || options.resume) return point;
  if (point->journal.rows.size() < definition.case_count())
    std::cerr << options.study << ": note: " << point->directory.string() << " holds " << point->journal.rows.size()
              << " rows of an unfinished run of this study, which this run replaces (--resume goes on from them)\n";
  return std::nullopt;
}

/// The kept cases (study.keep) of `rows` from the output directory `from` into `to`, as hard
/// links (a resumed study's from the outputs it goes on from, a merge's from its shards).
void carry_kept_cases(const std::filesystem::path& from, const std::vector<tsm::study::CaseResult>& rows,
                      const std::filesystem::path& to) {
  namespace fs = std::filesystem;
  for (const tsm::study::CaseResult& row : rows) {
    const fs::path kept = from / "cases" / std::to_string(row.index + 1);
    std::error_code error;
    if (!fs::exists(kept, error)) continue;
    fs::create_directories(to / "cases", error);
    fs::copy(kept, to / "cases" / kept.filename(), fs::copy_options::recursive | fs::copy_options::create_hard_links, error);
    if (error) throw tsm::io::SystemError(kept.string(), error.message());
  }
}

/// The study's closing line on stderr; returns the exit code.
int report_study(const StudyOptions& options, size_t total, const std::vector<tsm::study::CaseResult>& rows) {
  const auto bad = [](const tsm::study::CaseResult& r) { return r.status == "bad-input"; };
  const auto stopped = [](const tsm::study::CaseResult& r) { return r.status == "interrupted"; };
  const size_t failed = std::count_if(rows.begin(), rows.end(), [](const auto& r) { return !r.converged; });
  const size_t invalid = std::count_if(rows.begin(), rows.end(), bad);
  const size_t interrupted = std::count_if(rows.begin(), rows.end(), stopped);
  std::cerr << options.study << ": ";
  if (rows.size() < total || interrupted > 0) {
    const char* signal = tsm::app::stop_signal_name();
    std::cerr << (signal ? signal : "stop request") << ": interrupted after " << rows.size() << " of " << total
              << " cases (" << interrupted << " of them stopped at a step boundary, status interrupted), ";
  } else {
    std::cerr << rows.size() << " cases, ";
  }
  std::cerr << failed - invalid - interrupted << " did not converge";
  // A model the sweep made invalid is most often a typo in the study (a path to a key the model
  // does not have): the first such case's reason, on the terminal, not only in the rows.
  if (invalid > 0) {
    const auto first = std::find_if(rows.begin(), rows.end(), bad);
    std::cerr << ", " << invalid << " had a model the sweep made invalid (bad-input; case " << first->index + 1 << ": "
              << first->message << ")";
  }
  std::cerr << "; rows in " << options.out << "/study.csv and study.json\n";
  return failed == 0 && rows.size() == total ? exit_converged : exit_not_converged;
}

/// The study's cases on the Dask cluster at options.scheduler (scripts/study_cluster.py appends
/// their rows to the journal as shards end); the outputs from the journal. Returns the exit status.
int study_on_cluster(const StudyOptions& options, const tsm::study::Study& definition) {
  if (options.resume || !options.shard.empty()) {
    std::cerr << options.study << ": --scheduler: not with --resume or --shard (the cluster's run is one run: a worker "
              << "lost has its cases run again elsewhere)\n";
    return exit_bad_input;
  }
  tsm::app::install_stop_signals();  // Ctrl-C reaches the script too: the rows of the shards ended are written
  tsm::io::OutputDirectory output(options.out, {"study.csv", "study.json", "cases", tsm::study::journal_name});
  const std::filesystem::path journal = output.path() / tsm::study::journal_name;
  { tsm::study::StudyJournal header(journal, definition, {}); }
  const int status = run_script("study_cluster.py", {python_package_directory(), options.study, options.scheduler, journal.string(),
                                                     options.quiet ? "quiet" : "progress"});
  if (status == exit_bad_input) return exit_bad_input;  // the script said why
  if (status < 0 || status > exit_not_converged) {
    std::cerr << options.study << ": --scheduler: the cluster's script (scripts/study_cluster.py) failed\n";
    return exit_system;
  }
  std::vector<tsm::study::CaseResult> rows = tsm::study::read_journal(journal, definition).rows;
  { tsm::study::StudyJournal rewritten(journal, definition, rows); }  // in case order
  tsm::study::write_study(output.path().string(), definition, rows);
  output.commit();
  return report_study(options, definition.case_count(), rows);
}

}  // namespace

int study(const StudyOptions& options) {
  omp_set_num_threads(1);  // the cases run in parallel; each one on one thread
  tsm::study::Study definition;
  try {
    definition = tsm::study::read_study_file(options.study);
  } catch (const tsm::io::InputError& e) {
    std::cerr << options.study << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  if (const std::optional<std::string> invalid = tsm::study::invalid_in_every_case(definition)) {
    std::cerr << options.study << ": " << *invalid << '\n';
    return exit_bad_input;
  }
  tsm::study::StudyShard shard;
  if (!options.scheduler.empty()) return study_on_cluster(options, definition);
  std::optional<tsm::study::ResumePoint> from;
  try {
    if (!options.shard.empty()) shard = parse_shard(options.shard);
    from = resume_point(options, definition);
  } catch (const tsm::io::InputError& e) {
    std::cerr << options.study << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  const tsm::solver::StopRequest& stop = tsm::app::install_stop_signals();
  tsm::io::OutputDirectory output(options.out, {"study.csv", "study.json", "cases", tsm::study::journal_name},
                                  from && from->temporary ? from->directory : std::filesystem::path());  // as a run's (run above)
  std::vector<tsm::study::CaseResult> resumed;
  if (from)  // a journal of another share of the cases keeps only this run's
    for (tsm::study::CaseResult& row : from->journal.rows)
      if (shard.holds(row.index)) resumed.push_back(std::move(row));
  if (from && !from->temporary && definition.keep) carry_kept_cases(from->directory, resumed, output.path());
  tsm::study::StudyJournal journal(output.path() / tsm::study::journal_name, definition, resumed);
  const size_t total = shard.cases(definition.case_count());
  size_t done = resumed.size(), not_converged = 0;
  for (const auto& row : resumed) not_converged += row.converged ? 0 : 1;
  if (from && !options.quiet)
    std::cerr << options.study << ": resuming: " << done << " of " << total << " cases done (" << from->directory.string() << ")\n";
  // On a terminal a bar with the time left; elsewhere a line per case.
  const bool bar = tsm::app::stderr_is_terminal();
  tsm::app::LiveLine live(std::cerr, bar);
  const auto started = std::chrono::steady_clock::now();
  const auto progress = [&](const tsm::study::CaseResult& row) {
    journal.append(row);
    ++done;
    not_converged += row.converged ? 0 : 1;
    if (options.quiet) return;
    if (bar) {
      const auto elapsed = std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - started);
      live.passing(tsm::app::progress_bar(done, total, not_converged, elapsed));
      return;
    }
    std::cerr << "case " << row.index + 1 << '/' << definition.case_count();
    for (size_t p = 0; p < definition.parameters.size(); ++p)
      std::cerr << "  " << definition.parameters[p].name << ' ' << definition.parameters[p].labels[row.choice[p]];
    std::cerr << "  " << row.status << "  " << row.steps << " steps, " << row.iterations << " iterations  [" << done
              << " done]\n";
  };
  // Ctrl-C: no new case starts, the running ones stop at their next step; the rows of the cases run are written.
  const std::vector<tsm::study::CaseResult> rows =
      tsm::study::run_study(definition, options.jobs, output.path().string(), progress, &stop, std::move(resumed), shard);
  live.finish();
  tsm::study::write_study(output.path().string(), definition, rows);
  output.commit();
  return report_study(options, total, rows);
}


int study_merge(const MergeOptions& options) {
  namespace fs = std::filesystem;
  tsm::study::Study definition;
  std::map<size_t, std::pair<tsm::study::CaseResult, fs::path>> merged;  // by case: its row and the shard holding it
  size_t repeated = 0;
  try {
    definition = tsm::study::read_study_file(options.study);
    for (const std::string& shard : options.shards) {
      const fs::path journal = fs::path(shard) / tsm::study::journal_name;
      if (!fs::is_regular_file(journal))
        throw tsm::io::InputError(shard, std::string("holds no ") + tsm::study::journal_name + ": not an output directory of tsmframe study");
      for (tsm::study::CaseResult& row : tsm::study::read_journal(journal, definition).rows) {
        const size_t k = row.index;
        if (!merged.try_emplace(k, std::move(row), shard).second) ++repeated;
      }
    }
  } catch (const tsm::io::InputError& e) {
    std::cerr << options.study << ": " << e.what() << '\n';
    return exit_bad_input;
  }
  tsm::io::OutputDirectory output(options.out, {"study.csv", "study.json", "cases", tsm::study::journal_name});
  std::vector<tsm::study::CaseResult> rows;
  for (auto& [k, entry] : merged) {
    if (definition.keep) carry_kept_cases(entry.second, {entry.first}, output.path());
    rows.push_back(std::move(entry.first));
  }
  { tsm::study::StudyJournal journal(output.path() / tsm::study::journal_name, definition, rows); }
  tsm::study::write_study(output.path().string(), definition, rows);
  output.commit();
  const size_t total = definition.case_count();
  const size_t failed = std::count_if(rows.begin(), rows.end(), [](const auto& r) { return !r.converged; });
  std::cerr << options.study << ": merged " << rows.size() << " of " << total << " cases from " << options.shards.size()
            << " directories";
  if (repeated > 0) std::cerr << " (" << repeated << " cases held twice: the first directory's row kept)";
  if (rows.size() < total) {
    size_t first = 0;
    while (merged.count(first)) ++first;
    std::cerr << "; " << total - rows.size() << " cases missing (the first: case " << first + 1
              << "; its shard's run with --resume runs it)";
  }
  std::cerr << "; " << failed << " did not converge; rows in " << options.out << "/study.csv and study.json\n";
  return rows.size() == total && failed == 0 ? exit_converged : exit_not_converged;
}

}  // namespace tsm::app

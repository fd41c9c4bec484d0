#pragma once
// Running a study's cases (study.hpp): each case is the base model with its parameters'
// assignments, run on its own, the cases in parallel over the machine's cores, one row each. A
// case that fails — bad input after substitution, non-convergence, running out of memory — is a
// row too, never a crash of the sweep.

#include <functional>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tsmframe/solver/stop_request.hpp"
#include "tsmframe/study/study.hpp"

namespace tsm::study {

/// One row of the study: how one case ended.
struct CaseResult {
  size_t index = 0;
  std::vector<size_t> choice;       ///< value index per parameter
  std::string status;               ///< status_name, or "bad-input"
  bool converged = false;
  int steps = 0;                    ///< converged steps
  int iterations = 0;               ///< all Newton iterations, failed attempts included
  int last_iterations = 0;          ///< iterations of the last attempt
  double load_factor = 0.0;         ///< λ at the last converged step
  /// The tangent's negative eigenvalues at the last converged step: 0 a stable end state, n > 0
  /// an unstable one; −1 unknown (a contact active, a follower load, no converged step).
  int negative_eigenvalues = -1;
  std::string notes;                ///< the run's remarks on its path (RunResult::notes), one after another
  double seconds = 0.0;
  std::string message;
  // The first contact's story (when the model has contacts):
  int contact_first_element = 0;    ///< element id where it first touched (0: never)
  double contact_max_alpha_first = 0.0;  ///< largest α reached there at a converged step
  int contact_last_element = 0;     ///< element id at the last step in contact
  int contact_elements_passed = 0;  ///< element ends passed after the first element
  /// Per record: its value, NaN where the case has none (no converged step; a contact not
  /// touching at its last step for contact_xi).
  std::vector<double> recorded;
};

/// The share of a study's cases one run takes (`tsmframe study --shard I/N`, a job array's task):
/// case k (from 0) where k mod count = index, so that cases alike in cost spread over the shards.
struct StudyShard {
  size_t index = 0;
  size_t count = 1;
  bool holds(size_t k) const { return k % count == index; }
  /// How many of `total` cases it holds.
  size_t cases(size_t total) const { return total / count + (index < total % count ? 1 : 0); }
};

/// Runs every case on `threads` threads (0: all cores). `progress` is called after each case.
/// Whatever a case throws is its row (status "bad-input", the reason in its message) but
/// io::SystemError (the system failed, not the case); that and what `progress` throws stop the
/// cases and are rethrown here, after every thread has ended. Each case's run is held to its
/// share of the machine's memory as the study starts (io::memory_budget(cases run at once)): a
/// case beyond it is a row too, refused before its memory is spent. With study.keep, each case's
/// results.json and steps.csv go to `keep_directory`/cases/<case>/. A requested `stop` starts
/// no new case and ends the running ones at their next step (status "interrupted"). The cases
/// of `done` (rows of an earlier run of the study, study_journal.hpp) are not run again, nor told
/// to `progress`. Only the cases `shard` holds run. Returns the rows of the cases run and done,
/// in case order.
std::vector<CaseResult> run_study(const Study& study, int threads, const std::string& keep_directory,
                                  const std::function<void(const CaseResult&)>& progress = {},
                                  const solver::StopRequest* stop = nullptr, std::vector<CaseResult> done = {},
                                  const StudyShard& shard = {});

/// The value index per parameter of case `index` (from 0), the first parameter varying slowest.
std::vector<size_t> case_choice(const Study& study, size_t index);
/// The case's model JSON: the base model with the case's assignments, in order. Throws
/// io::InputError where an assignment's pointer names no place in the model so far (assignment.hpp).
nlohmann::json case_model(const Study& study, const std::vector<size_t>& choice);

/// Why no case can run: the first and the last case's models are refused at the same JSON path
/// for the same reason (a fault of the base model no parameter reaches): "model: PATH: reason …"; nothing
/// when either is valid or they differ. Read before the study runs, so that such a study is bad
/// input (exit 2) rather than a million rows of it.
std::optional<std::string> invalid_in_every_case(const Study& study);

}  // namespace tsm::study

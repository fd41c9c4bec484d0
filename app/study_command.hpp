#pragma once
// `tsmframe study` and `tsmframe study-merge`: a study's cases run here (all, or one shard of
// them for a job array), with the journal that --resume goes on from; shards' outputs joined
// into the whole study's (study/study_journal.hpp, docs/format.md).

#include <string>
#include <vector>

namespace tsm::app {

struct StudyOptions {
  std::string study;
  std::string out = "out-study";  // beside a run's `out`, not in it: a run replaces its directory whole
  bool quiet = false;
  int jobs = 0;         // 0: all cores
  bool resume = false;  // go on from the rows of an earlier run (study_journal.hpp)
  std::string shard;    // "I/N": the cases k (from 1) with (k − 1) mod N = I − 1; empty: all
  std::string scheduler;  // a Dask scheduler's address: the cases run on its workers; empty: here
};

/// Runs the study as `options` say; returns the exit status (exit_codes.hpp).
int study(const StudyOptions& options);

struct MergeOptions {
  std::string study;
  std::vector<std::string> shards;  ///< output directories of `tsmframe study --shard`
  std::string out = "out-study";
};

/// Joins shards' rows and kept cases into the whole study's outputs; returns the exit status.
int study_merge(const MergeOptions& options);

}  // namespace tsm::app

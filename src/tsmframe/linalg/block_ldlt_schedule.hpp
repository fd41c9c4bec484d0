#pragma once
// How the block LDLᵀ (block_ldlt) shares out its rows, from the pattern alone: independent
// subtrees of the elimination tree as parallel tasks; the rows above them level by level (rows
// of one level are not ancestors of one another), grouped into stages — a level of several
// rows, or a path of single-row levels whose top, where it fills at least half of its lower
// triangle, is factorised as one dense matrix. It depends on the pattern, never on the number
// of threads: every row gets the same arithmetic in the same order, so results are bit-identical.

#include <cstddef>
#include <vector>

#include "tsmframe/linalg/block_matrix.hpp"

namespace tsm::linalg {

struct BlockLDLTSchedule {
  /// Task t: rows task_rows[task_start[t] .. task_start[t+1]), ascending.
  std::vector<int> task_start, task_rows;
  std::vector<int> top_rows;     ///< rows in no task, level by level (ascending within a level)
  std::vector<int> level_start;  ///< level l: top_rows[level_start[l] .. level_start[l+1])
  bool parallel_top = false;     ///< enough rows above the tasks to run their stages in parallel
  bool parallel_tasks = false;   ///< several tasks, in a matrix big enough to share out (util::smallest_shared_model)
  bool parallel_top_levels = false;  ///< the solves: the levels hold enough rows side by side
  bool team = false;  ///< a matrix big enough for the rows above the tasks to run on every thread
  /// Stages of top_rows [begin, end): a level of several rows, or a path of single-row levels.
  struct Stage {
    int begin = 0, end = 0;
    bool path = false;
    /// A path whose rows' entries from its first column on lie in its own columns and fill at
    /// least half of its lower triangle: that part is factorised as a dense matrix.
    bool dense = false;
  };
  std::vector<Stage> stages;
  std::vector<int> split;           ///< per entry of top_rows in a path: its first entry (row index t) in a path column
  std::vector<int> deferred_start;  ///< per entry of top_rows in a path: its prefix's place in the deferred sums
  size_t deferred = 0;              ///< blocks of the path rows' deferred sums, in all

  int task_count() const { return static_cast<int>(task_start.size()) - 1; }
  int level_count() const { return static_cast<int>(level_start.size()) - 1; }
};

/// The schedule of `matrix` (its pattern holding its fill), read by rows, with its elimination
/// tree `parent`.
BlockLDLTSchedule schedule_block_ldlt(const BlockMatrix& matrix, const BlockRows& rows, const std::vector<int>& parent);

/// What a factorisation by rows keeps of its pattern (BlockLDLT, BlockLU): the filled lower
/// triangle by rows — row k's entries (k, i), i < k, are start[k] .. start[k+1] in position
/// (their index in value) with their columns i ascending in column, and whether each is fill
/// (zeroed as its row starts) — a slot map (during row k: column i → the entry (k, i)) and the
/// schedule of its rows.
struct FactorRows {
  std::vector<int> start, position, column;
  std::vector<unsigned char> fill;
  std::vector<int> slot;
  BlockLDLTSchedule schedule;
};
/// `rows` for `matrix` (filled_pattern's checks; storage reused).
void analyze_rows(const BlockMatrix& matrix, FactorRows& rows);

}  // namespace tsm::linalg

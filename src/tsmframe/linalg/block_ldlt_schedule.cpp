#include "tsmframe/linalg/block_ldlt_schedule.hpp"

#include <algorithm>
#include <utility>

#include "tsmframe/util/first_touch.hpp"
#include "tsmframe/util/parallel_for.hpp"

namespace tsm::linalg {
namespace {

constexpr size_t parallel_rows_above = 256;  // fewer rows above the tasks: run them serially
constexpr int dense_path_rows = 32;         // a shorter path is formed row by row, never dense

/// The tasks (into s.task_start, s.task_rows); returns each row's task, −1 above them.
std::vector<int> partition_tasks(const std::vector<int>& parent, BlockLDLTSchedule& s) {
  const int n = static_cast<int>(parent.size());
  // Tasks: the largest subtrees of at most `limit` blocks (and at least 64). The limit is the
  // largest that still gives 8 tasks — enough to keep two or more cores busy, as large as
  // possible so that few rows are left above them; failing that, the largest that gives 2 (the
  // two branches of a single long member, elimination_order); else n / 16. It depends on the
  // pattern only (the solves' arithmetic follows the partition), never on the thread count.
  // Parents come after children, so one ascending pass sums subtree sizes and one descending
  // pass hands every block to its task.
  std::vector<int> size(n, 1), task(n, -1);
  for (int k = 0; k < n; ++k)
    if (parent[k] >= 0) size[parent[k]] += size[k];
  auto assign_tasks = [&](int limit) {
    int tasks = 0;
    for (int k = n - 1; k >= 0; --k) {
      const int p = parent[k];
      if (p >= 0 && task[p] >= 0) task[k] = task[p];
      else if (size[k] <= limit && size[k] >= 64) task[k] = tasks++;
      else task[k] = -1;
    }
    return tasks;
  };
  // The largest limit from `lo` up that still gives `wanted` tasks (assign_tasks(lo) does).
  auto largest_limit = [&](int lo, int wanted) {
    int hi = n;
    while (lo < hi) {
      const int mid = lo + (hi - lo + 1) / 2;
      if (assign_tasks(mid) >= wanted) lo = mid;
      else hi = mid - 1;
    }
    return lo;
  };
  constexpr int wanted_tasks = 8;
  int limit = std::max(1, n / 16);
  if (assign_tasks(limit) >= wanted_tasks) limit = largest_limit(limit, wanted_tasks);
  else if (const int half = std::max(64, n / 2); assign_tasks(half) >= 2) limit = largest_limit(half, 2);  // a long member's two branches
  const int tasks = assign_tasks(limit);
  s.task_start.assign(tasks + 1, 0);
  for (int k = 0; k < n; ++k)
    if (task[k] >= 0) ++s.task_start[task[k] + 1];
  for (int t = 0; t < tasks; ++t) s.task_start[t + 1] += s.task_start[t];
  s.task_rows.resize(s.task_start[tasks]);
  std::vector<int> next(s.task_start.begin(), s.task_start.end() - 1);
  for (int k = 0; k < n; ++k)
    if (task[k] >= 0) s.task_rows[next[task[k]]++] = k;
  return task;
}

/// The rows above the tasks, level by level (into s.top_rows, s.level_start); returns the first
/// row of the tree's top chain.
int order_by_level(const std::vector<int>& parent, const std::vector<int>& task, BlockLDLTSchedule& s) {
  const int n = static_cast<int>(parent.size());

  // The rows above the tasks, by level: one more than the highest level among a row's children
  // above the tasks (1 if none). Rows of one level are not ancestors of one another, so their
  // patterns — and the columns they read and write — are disjoint: they run concurrently.
  // The tree's top chain: the last rows, each the parent of the one before (a frame's last
  // separator, numbered consecutively by elimination_order). Its rows take one level each after
  // every other row's, so that they form the final path stage whatever the levels of the
  // branches beside them (a member hanging off one of its joints would otherwise share a level
  // with it and cut the chain into pieces too short to factorise as one dense block).
  int chain = n;
  if (n > 0 && task[n - 1] < 0) {
    chain = n - 1;
    while (chain > 0 && parent[chain - 1] == chain && task[chain - 1] < 0) --chain;
  }
  std::vector<int> level(n, 0);
  int levels = 0;
  for (int k = 0; k < chain; ++k) {  // ascending: children first
    if (task[k] >= 0) continue;
    level[k] = std::max(level[k], 1);
    levels = std::max(levels, level[k]);
    if (parent[k] >= 0) level[parent[k]] = std::max(level[parent[k]], level[k] + 1);
  }
  for (int k = chain; k < n; ++k) level[k] = ++levels;
  s.level_start.assign(levels + 1, 0);
  for (int k = 0; k < n; ++k)
    if (task[k] < 0) ++s.level_start[level[k]];
  for (int l = 0; l < levels; ++l) s.level_start[l + 1] += s.level_start[l];
  s.top_rows.resize(s.level_start[levels]);
  std::vector<int> place(s.level_start.begin(), s.level_start.end() - 1);
  for (int k = 0; k < n; ++k)
    if (task[k] < 0) s.top_rows[place[level[k] - 1]++] = k;
  return chain;
}

/// The stages of the rows above the tasks (into s.stages, s.split, s.deferred_start, s.deferred).
void form_stages(const BlockMatrix& a, const BlockRows& rows, BlockLDLTSchedule& s) {
  const int levels = s.level_count();
  // Stages of the rows above the tasks: each level of several rows, and each run of single-row
  // levels — a path of the tree, where every row's pattern below the path is final before the
  // path starts (its other descendants sit in lower levels). A path row's split: its first
  // entry in a column of the path.
  // A path's top rows with consecutive numbers (the tree's top supernode, or one like it: a
  // frame lattice's last separator) have all their other descendants below the lowest of them,
  // so from that row on their entries lie in their own columns only. Where such a run is long
  // and fills at least half of its lower triangle, it becomes a path of its own whose rows,
  // after the passes over their prefixes, are factorised as one dense matrix (passes only).
  s.stages.clear();
  s.split.assign(s.top_rows.size(), 0);
  s.deferred_start.assign(s.top_rows.size(), 0);
  size_t& deferred = s.deferred;
  auto add_path = [&](int begin, int end, bool dense) {
    const int lowest = s.top_rows[begin];
    size_t entries = 0;
    for (int q = begin; q < end; ++q) {
      const int k = s.top_rows[q];
      s.split[q] = static_cast<int>(std::lower_bound(rows.column.begin() + rows.start[k], rows.column.begin() + rows.start[k + 1], lowest) -
                                   rows.column.begin());
      s.deferred_start[q] = static_cast<int>(deferred);
      deferred += s.split[q] - rows.start[k];
      entries += rows.start[k + 1] - s.split[q];
    }
    const size_t count = end - begin;
    dense = dense && 4 * entries >= count * (count - 1);
    s.stages.push_back({begin, end, true, dense});
  };
  for (int l = 0; l < levels;) {
    if (s.level_start[l + 1] - s.level_start[l] > 1) {
      s.stages.push_back({s.level_start[l], s.level_start[l + 1], false});
      ++l;
      continue;
    }
    int m = l;
    while (m < levels && s.level_start[m + 1] - s.level_start[m] == 1) ++m;
    const int begin = s.level_start[l], end = s.level_start[m];
    int run = end - 1;  // the run of consecutive rows at the path's top, from its lowest
    while (run > begin && s.top_rows[run - 1] == s.top_rows[run] - 1) --run;
    // Of that run, the longest top part whose lower triangle is at least half filled (the one
    // factorised dense): the run's lower rows may be a member's nodes, one entry each, hanging
    // from the separator's first joint. The part from row q on holds the entries of its columns
    // up to the path's last row.
    int dense_from = end;
    for (int q = end - 1, entries = 0; q >= run; --q) {
      const int k = s.top_rows[q], last = s.top_rows[end - 1], count = end - q;
      for (int p = a.column[k] + 1; p < a.column[k + 1] && a.row[p] <= last; ++p) ++entries;
      if (4 * static_cast<long>(entries) >= static_cast<long>(count) * (count - 1)) dense_from = q;
    }
    if (s.parallel_top && end - dense_from >= dense_path_rows) {
      if (dense_from > begin) add_path(begin, dense_from, false);
      add_path(dense_from, end, true);
    } else {
      add_path(begin, end, false);
    }
    l = m;
  }
}

}  // namespace

BlockLDLTSchedule schedule_block_ldlt(const BlockMatrix& a, const BlockRows& rows, const std::vector<int>& parent) {
  const int n = static_cast<int>(parent.size());
  BlockLDLTSchedule s;
  const std::vector<int> task = partition_tasks(parent, s);
  const int chain = order_by_level(parent, task, s);
  // Level by level in parallel only where levels hold several rows: a path (one row per level)
  // would pay a barrier per row for nothing.
  int shared = 0;  // rows in levels of two or more
  for (int l = 0; l < s.level_count(); ++l)
    if (s.level_start[l + 1] - s.level_start[l] > 1) shared += s.level_start[l + 1] - s.level_start[l];
  // In parallel only where the rows above the tasks are many (else a barrier per stage costs
  // more than it saves), or where the top chain is long enough for a dense block: a frame
  // lattice has few rows above its tasks but most of its work there, in the last separator.
  s.parallel_top = s.top_rows.size() >= parallel_rows_above || n - chain >= dense_path_rows;
  s.parallel_tasks = s.task_count() > 1 && n >= util::smallest_shared_model;
  form_stages(a, rows, s);
  // The solves go level by level (a barrier per level): only where levels hold several rows.
  // A small matrix keeps the stages' arithmetic (paths, a dense top: bit-identical either way)
  // but runs them on one thread: there, starting and waking the second thread costs more than
  // the stages' work (util::smallest_shared_model).
  s.team = n >= util::smallest_shared_model;
  s.parallel_top_levels = s.parallel_top && 2 * shared >= static_cast<int>(s.top_rows.size()) && s.team;
  return s;
}

void analyze_rows(const BlockMatrix& matrix, FactorRows& rows) {
  FilledPattern pattern = filled_pattern(matrix);
  rows.schedule = schedule_block_ldlt(matrix, pattern.rows, pattern.parent);
  rows.start = std::move(pattern.rows.start);
  rows.column = std::move(pattern.rows.column);
  rows.position = std::move(pattern.rows.position);
  rows.fill = std::move(pattern.row_fill);
  util::assign_touched(rows.slot, static_cast<std::size_t>(matrix.size), -1);
}

}  // namespace tsm::linalg

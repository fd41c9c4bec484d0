#include "tsmframe/solver/block_ldlt.hpp"

#include "tsmframe/util/elimination_tree.hpp"
#include "tsmframe/util/first_touch.hpp"
#include "tsmframe/util/parallel_for.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <omp.h>

namespace tsm::solver {
namespace {

constexpr size_t parallel_rows_above = 256;  // fewer rows above the tasks: run them serially
constexpr int path_rows_per_thread = 8;      // a thread's run of consecutive path rows (false sharing)
constexpr int dense_path_rows = 32;         // a shorter path is formed row by row, never dense

// The factorisation's 3×3 block products are arithmetic-bound (a lattice frame's top separator):
// on x86-64 they are also compiled for AVX2 + FMA, picked at load time where the CPU has them
// (GCC function multi-versioning; the baseline build still runs anywhere). 30 % less time
// factorising the lattice's tangent on one core. Results then depend on the CPU's instruction
// set in their last bits (FMA rounds once), never on the number of threads.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define TSM_BLOCK_KERNEL __attribute__((target_clones("default", "arch=x86-64-v3")))
#else
#define TSM_BLOCK_KERNEL
#endif

/// C −= Z Bᵀ for 3×3 blocks (column-major, 9 doubles each) with Z fixed: the factorisation's
/// inner update, streaming B down a column. Z is spread over lanes once, so that each update is
/// two 4-wide and one scalar multiply-add chain on C's entries 0–3, 4–7 and 8, with B's columns
/// permuted into place: 2.5× Eigen's 3×3 product on blocks in cache. Every load and store stays
/// inside its own block (a neighbouring block may be another thread's). Entry by entry it is the
/// same arithmetic as (Z Bᵀ)(r, c) = Z(r, 0) B(c, 0) + Z(r, 1) B(c, 1) + Z(r, 2) B(c, 2).
class RankThreeUpdate {
 public:
  using Lanes = double __attribute__((vector_size(32), aligned(8)));
  using Picks = long __attribute__((vector_size(32)));
  explicit RankThreeUpdate(const Block& z) {
    const double* v = z.data();  // Z(r, t) at v[r + 3t]
    for (int t = 0; t < 3; ++t) {
      first_[t] = Lanes{v[3 * t], v[3 * t + 1], v[3 * t + 2], v[3 * t]};       // rows of C entries 0-3: 0 1 2 0
      second_[t] = Lanes{v[3 * t + 1], v[3 * t + 2], v[3 * t], v[3 * t + 1]};  // entries 4-7: rows 1 2 0 1
      last_[t] = v[3 * t + 2];                                                  // entry 8: row 2
    }
  }
  __attribute__((always_inline)) inline void subtract_from(Block& c_block, const Block& b_block) const {
    const double* b = b_block.data();  // B(c, t) at b[c + 3t]
    double* c = c_block.data();
    Lanes b0, b1, b2, low, high;  // unaligned loads (memcpy): b2 = b[5..8], B(·, 2) in lanes 1-3
    __builtin_memcpy(&b0, b, sizeof b0);
    __builtin_memcpy(&b1, b + 3, sizeof b1);
    __builtin_memcpy(&b2, b + 5, sizeof b2);
    // Entries 0-3 are C(0,0) C(1,0) C(2,0) C(0,1): columns 0 0 0 1; entries 4-7 C(1,1) C(2,1) C(0,2) C(1,2).
    __builtin_memcpy(&low, c, sizeof low);
    __builtin_memcpy(&high, c + 4, sizeof high);
    low -= first_[0] * __builtin_shuffle(b0, Picks{0, 0, 0, 1}) + first_[1] * __builtin_shuffle(b1, Picks{0, 0, 0, 1}) +
           first_[2] * __builtin_shuffle(b2, Picks{1, 1, 1, 2});
    high -= second_[0] * __builtin_shuffle(b0, Picks{1, 1, 2, 2}) + second_[1] * __builtin_shuffle(b1, Picks{1, 1, 2, 2}) +
            second_[2] * __builtin_shuffle(b2, Picks{2, 2, 3, 3});
    c[8] -= last_[0] * b[2] + last_[1] * b[5] + last_[2] * b[8];
    __builtin_memcpy(c, &low, sizeof low);
    __builtin_memcpy(c + 4, &high, sizeof high);
  }

 private:
  Lanes first_[3], second_[3];
  double last_[3];
};

/// Rows of the lower triangle: row k lists the columns i < k with an entry (k, i), ascending,
/// and where that entry is stored.
struct Rows {
  std::vector<int> start, column, position;
};

Rows rows_of(const BlockMatrix& a) {
  const int n = a.size;
  Rows r;
  util::assign_touched(r.start, n + 1, 0);
  for (int c = 0; c < n; ++c)
    for (int p = a.column[c]; p < a.column[c + 1]; ++p)
      if (a.row[p] > c) ++r.start[a.row[p] + 1];
  for (int k = 0; k < n; ++k) r.start[k + 1] += r.start[k];
  util::resize_touched(r.column, r.start[n]);
  util::resize_touched(r.position, r.start[n]);
  std::vector<int> next(r.start.begin(), r.start.end() - 1);
  for (int c = 0; c < n; ++c)  // ascending c: every row lists its columns ascending
    for (int p = a.column[c]; p < a.column[c + 1]; ++p)
      if (a.row[p] > c) {
        r.column[next[a.row[p]]] = c;
        r.position[next[a.row[p]]++] = p;
      }
  return r;
}

/// Blocks i < k on the paths from each entry (k, i) up the elimination tree: the pattern of row
/// k of L, written to stack[top .. n); returns top (cs_ereach).
int reach(const Rows& rows, int k, const std::vector<int>& parent, std::vector<int>& flag, std::vector<int>& stack) {
  const int n = static_cast<int>(parent.size());
  int top = n;
  flag[k] = k;
  for (int t = rows.start[k]; t < rows.start[k + 1]; ++t) {
    int i = rows.column[t];
    int len = 0;
    for (; flag[i] != k; i = parent[i]) {
      stack[len++] = i;  // the path goes to the front of stack (its tail is not yet used)
      flag[i] = k;
    }
    while (len > 0) stack[--top] = stack[--len];
  }
  return top;
}

}  // namespace

void add_fill(BlockMatrix& a) {
  const int n = a.size;
  const Rows rows = rows_of(a);
  const std::vector<int> parent = util::elimination_tree(rows.start, rows.column, n);
  // Row k of L, for every k: (k, i) pairs, k ascending; then counted into columns.
  std::vector<int> flag(n, -1), stack(n, 0), column(n + 1, 0), entries_row, entries_column;
  for (int k = 0; k < n; ++k) {
    const int top = reach(rows, k, parent, flag, stack);
    for (int t = top; t < n; ++t) {
      entries_row.push_back(k);
      entries_column.push_back(stack[t]);
      ++column[stack[t] + 1];
    }
  }
  for (int c = 0; c < n; ++c) column[c + 1] += column[c] + 1;  // + the diagonal
  std::vector<int> row, next(n);
  util::resize_touched(row, column[n]);
  for (int c = 0; c < n; ++c) {
    row[column[c]] = c;  // diagonal first
    next[c] = column[c] + 1;
  }
  for (size_t e = 0; e < entries_row.size(); ++e) row[next[entries_column[e]]++] = entries_row[e];  // rows ascending
  // The fill: the entries of the new pattern that the old one lacks (both ascending per column).
  std::vector<unsigned char> fill;
  util::assign_touched(fill, row.size(), static_cast<unsigned char>(1));
  bool any = false;
  for (int c = 0; c < n; ++c) {
    int q = column[c];
    for (int p = a.column[c]; p < a.column[c + 1]; ++p) {
      for (; row[q] < a.row[p]; ++q) any = true;
      fill[q++] = 0;
    }
    any = any || q < column[c + 1];
  }
  a.column = std::move(column);
  a.row = std::move(row);
  util::resize_touched(a.value, a.row.size());  // the tangent's largest array: its pages mapped in at once
  for (Block& b : a.value) b.setZero();
  if (any) a.fill = std::move(fill);
  else a.fill.clear();
}

void BlockLDLT::analyze(const BlockMatrix& a) {
  const int n = size_ = a.size;
  const Rows rows = rows_of(a);
  // The pattern must hold its fill. Then it is closed under elimination: each column's rows
  // below its first one (the column's parent in the elimination tree) are rows of the parent's
  // column too — checked by one merge per column, and the tree read off the pattern.
  std::vector<int> parent(n, -1);
  for (int c = 0; c < n; ++c) {
    if (a.row[a.column[c]] != c) throw std::logic_error("BlockLDLT: a column does not start with its diagonal");
    if (a.column[c + 1] - a.column[c] < 2) continue;
    const int p = parent[c] = a.row[a.column[c] + 1];
    int q = a.column[p];
    for (int e = a.column[c] + 2; e < a.column[c + 1]; ++e) {
      while (q < a.column[p + 1] && a.row[q] < a.row[e]) ++q;
      if (q == a.column[p + 1] || a.row[q] != a.row[e])
        throw std::logic_error("BlockLDLT: the block pattern lacks the fill of its factor (add_fill)");
    }
  }
  row_start_ = rows.start;
  row_column_ = rows.column;
  row_position_ = rows.position;
  row_fill_.clear();
  if (!a.fill.empty()) {
    row_fill_.resize(row_position_.size());
    for (size_t t = 0; t < row_position_.size(); ++t) row_fill_[t] = a.fill[row_position_[t]];
  }
  util::assign_touched(slot_, n, -1);

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
  task_start_.assign(tasks + 1, 0);
  for (int k = 0; k < n; ++k)
    if (task[k] >= 0) ++task_start_[task[k] + 1];
  for (int t = 0; t < tasks; ++t) task_start_[t + 1] += task_start_[t];
  task_rows_.resize(task_start_[tasks]);
  std::vector<int> next(task_start_.begin(), task_start_.end() - 1);
  for (int k = 0; k < n; ++k)
    if (task[k] >= 0) task_rows_[next[task[k]]++] = k;

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
  level_start_.assign(levels + 1, 0);
  for (int k = 0; k < n; ++k)
    if (task[k] < 0) ++level_start_[level[k]];
  for (int l = 0; l < levels; ++l) level_start_[l + 1] += level_start_[l];
  top_rows_.resize(level_start_[levels]);
  std::vector<int> place(level_start_.begin(), level_start_.end() - 1);
  for (int k = 0; k < n; ++k)
    if (task[k] < 0) top_rows_[place[level[k] - 1]++] = k;
  // Level by level in parallel only where levels hold several rows: a path (one row per level)
  // would pay a barrier per row for nothing.
  int shared = 0;  // rows in levels of two or more
  for (int l = 0; l < levels; ++l)
    if (level_start_[l + 1] - level_start_[l] > 1) shared += level_start_[l + 1] - level_start_[l];
  // In parallel only where the rows above the tasks are many (else a barrier per stage costs
  // more than it saves), or where the top chain is long enough for a dense block: a lattice of
  // one element per member has ~230 rows above its tasks, 74 % of the work, most of it in the
  // last separator (factorisation 7.7 → 5.6 ms on two threads; bench/README "Eleventh session").
  parallel_top_ = top_rows_.size() >= parallel_rows_above || n - chain >= dense_path_rows;
  parallel_tasks_ = tasks > 1 && n >= util::smallest_shared_model;
  // Stages of the rows above the tasks: each level of several rows, and each run of single-row
  // levels — a path of the tree, where every row's pattern below the path is final before the
  // path starts (its other descendants sit in lower levels). A path row's split: its first
  // entry in a column of the path.
  // A path's top rows with consecutive numbers (the tree's top supernode, or one like it: a
  // frame lattice's last separator) have all their other descendants below the lowest of them,
  // so from that row on their entries lie in their own columns only. Where such a run is long
  // and fills at least half of its lower triangle, it becomes a path of its own whose rows,
  // after the passes over their prefixes, are factorised as one dense matrix (passes only).
  stages_.clear();
  split_.assign(top_rows_.size(), 0);
  deferred_start_.assign(top_rows_.size(), 0);
  size_t deferred = 0;
  auto add_path = [&](int begin, int end, bool dense) {
    const int lowest = top_rows_[begin];
    size_t entries = 0;
    for (int q = begin; q < end; ++q) {
      const int k = top_rows_[q];
      split_[q] = static_cast<int>(std::lower_bound(row_column_.begin() + row_start_[k], row_column_.begin() + row_start_[k + 1], lowest) -
                                   row_column_.begin());
      deferred_start_[q] = static_cast<int>(deferred);
      deferred += split_[q] - row_start_[k];
      entries += row_start_[k + 1] - split_[q];
    }
    const size_t rows = end - begin;
    dense = dense && 4 * entries >= rows * (rows - 1);
    stages_.push_back({begin, end, true, dense});
  };
  for (int l = 0; l < levels;) {
    if (level_start_[l + 1] - level_start_[l] > 1) {
      stages_.push_back({level_start_[l], level_start_[l + 1], false});
      ++l;
      continue;
    }
    int m = l;
    while (m < levels && level_start_[m + 1] - level_start_[m] == 1) ++m;
    const int begin = level_start_[l], end = level_start_[m];
    int run = end - 1;  // the run of consecutive rows at the path's top, from its lowest
    while (run > begin && top_rows_[run - 1] == top_rows_[run] - 1) --run;
    // Of that run, the longest top part whose lower triangle is at least half filled (the one
    // factorised dense): the run's lower rows may be a member's nodes, one entry each, hanging
    // from the separator's first joint. The part from row q on holds the entries of its columns
    // up to the path's last row.
    int dense_from = end;
    for (int q = end - 1, entries = 0; q >= run; --q) {
      const int k = top_rows_[q], last = top_rows_[end - 1], rows = end - q;
      for (int p = a.column[k] + 1; p < a.column[k + 1] && a.row[p] <= last; ++p) ++entries;
      if (4 * static_cast<long>(entries) >= static_cast<long>(rows) * (rows - 1)) dense_from = q;
    }
    if (parallel_top_ && end - dense_from >= dense_path_rows) {
      if (dense_from > begin) add_path(begin, dense_from, false);
      add_path(dense_from, end, true);
    } else {
      add_path(begin, end, false);
    }
    l = m;
  }
  if (parallel_top_) deferred_z_.resize(deferred);  // the path rows' running sums, pass (1) to (2)
  else std::vector<Block>().swap(deferred_z_);
  dense_.resize(0, 0);
  // The solves go level by level (a barrier per level): only where levels hold several rows.
  // A small matrix keeps the stages' arithmetic (paths, a dense top: bit-identical either way)
  // but runs them on one thread: a ring of 80 elements between two plates spent 2.5× its time
  // starting and waking the second thread for them (74 % of its samples in libgomp).
  team_ = n >= util::smallest_shared_model;
  parallel_top_levels_ = parallel_top_ && 2 * shared >= static_cast<int>(top_rows_.size()) && team_;
}

TSM_BLOCK_KERNEL bool BlockLDLT::form_row(BlockMatrix& a, int k, int t_begin, int t_end, double* forward, int* slot, bool finish,
                         int defer_from, Block* deferred) {
  // Row k's entries (k, i), i ascending (a topological order: every dependency runs from a lower
  // to a higher block), hold A(k, i) and serve as the running sums z = A(k, i) − Σ L(k, j) D_j
  // L(i, j)ᵀ; each becomes L(k, i) = z D_i⁻¹. The diagonal block becomes D_k⁻¹. Entries
  // [t_begin, t_end) are formed here; a row may be formed in two calls (a prefix, then the rest
  // with `finish`): the running D_k and y_k wait in the diagonal block and in `forward`, and the
  // arithmetic is the same as in one call. With `defer_from`, updates into entries (k, r) of rows
  // r ≥ defer_from are left out and each entry's running sum z is kept in `deferred` instead
  // (apply_deferred adds them later, in the same order).
  const int first = row_start_[k], last = row_start_[k + 1];
  for (int t = first; t < last; ++t) slot[row_column_[t]] = row_position_[t];
  if (t_begin == first && !row_fill_.empty())  // the row's first call: its fill starts at zero (no entry of A)
    for (int t = first; t < last; ++t)
      if (row_fill_[t]) a.value[row_position_[t]].setZero();
  // D_k is symmetric: only its upper triangle is formed (d00 d01 d02 d11 d12 d22).
  Block& diagonal = a.value[a.column[k]];
  double d00 = diagonal(0, 0), d01 = diagonal(0, 1), d02 = diagonal(0, 2), d11 = diagonal(1, 1), d12 = diagonal(1, 2),
         d22 = diagonal(2, 2);
  for (int t = t_begin; t < t_end; ++t) {
    const int i = row_column_[t];
    Block& z = a.value[row_position_[t]];
    const Block lki = z * a.value[a.column[i]];  // L(k, i) = z D_i⁻¹ (D_i⁻¹ on column i's diagonal)
    // D_k −= L(k, i) zᵀ (symmetric): the upper triangle only.
    d00 -= lki.row(0).dot(z.row(0));
    d01 -= lki.row(0).dot(z.row(1));
    d02 -= lki.row(0).dot(z.row(2));
    d11 -= lki.row(1).dot(z.row(1));
    d12 -= lki.row(1).dot(z.row(2));
    d22 -= lki.row(2).dot(z.row(2));
    // Column i's rows r (i < r < k) update the running sums (k, r), streaming down the column:
    // they are the entries above (k, i) itself (rows ascending), all formed before row k.
    const int end = row_position_[t];
    const RankThreeUpdate update(z);
    for (int p = a.column[i] + 1; p < end && a.row[p] < defer_from; ++p) update.subtract_from(a.value[slot[a.row[p]]], a.value[p]);
    if (deferred) deferred[t - t_begin] = z;
    z = lki;
  }
  if (forward) {  // y_k = b_k − Σ L(k, i) y_i, the rows i < k being final
    Eigen::Map<Eigen::Vector3d> yk(forward + 3 * k);
    Eigen::Vector3d sum = yk;
    for (int t = t_begin; t < t_end; ++t)
      sum.noalias() -= a.value[row_position_[t]] * Eigen::Map<const Eigen::Vector3d>(forward + 3 * row_column_[t]);
    yk = sum;
  }
  if (!finish) {
    diagonal(0, 0) = d00, diagonal(0, 1) = d01, diagonal(0, 2) = d02, diagonal(1, 1) = d11, diagonal(1, 2) = d12,
    diagonal(2, 2) = d22;
    return true;
  }
  // D_k⁻¹ by cofactors of the symmetric block.
  Block d;
  d << d00, d01, d02, d01, d11, d12, d02, d12, d22;
  int negatives = 0;
  if (!invert_pivot(d, diagonal, &negatives)) return false;
  if (negatives > 0) thread_negatives_[omp_get_thread_num()].count += negatives;  // each thread its own line
  return true;
}

TSM_BLOCK_KERNEL void BlockLDLT::apply_deferred(BlockMatrix& a, int k, int t_end, int defer_from, const Block* deferred, int* slot) const {
  const int first = row_start_[k], last = row_start_[k + 1];
  for (int t = first; t < last; ++t) slot[row_column_[t]] = row_position_[t];
  for (int t = first; t < t_end; ++t) {
    const int i = row_column_[t], end = row_position_[t];
    int p = end;  // rows ascending: the deferred ones (≥ defer_from) end the stretch above (k, i)
    while (p > a.column[i] + 1 && a.row[p - 1] >= defer_from) --p;
    const RankThreeUpdate update(deferred[t - first]);
    for (; p < end; ++p) update.subtract_from(a.value[slot[a.row[p]]], a.value[p]);
  }
}

bool BlockLDLT::factorize_row(BlockMatrix& a, int k, double* forward) {
  return form_row(a, k, row_start_[k], row_start_[k + 1], forward, slot_.data(), true, std::numeric_limits<int>::max(), nullptr);
}

bool BlockLDLT::factorize(BlockMatrix& a, Eigen::VectorXd* forward_rhs) {
  factor_ = &a;
  negative_pivots_ = 0;
  thread_negatives_.assign(omp_get_max_threads(), {});
  double* forward = forward_rhs ? forward_rhs->data() : nullptr;
  // Rows of one subtree touch only that subtree's columns (their patterns are descendants):
  // the tasks run concurrently, each in ascending order.
  const int tasks = static_cast<int>(task_start_.size()) - 1;
  const bool tasks_ok = util::parallel_all_dynamic(0, tasks, parallel_tasks_, [&](int t) {
    for (int r = task_start_[t]; r < task_start_[t + 1]; ++r)
      if (!factorize_row(a, task_rows_[r], forward)) return false;
    return true;
  });
  if (!tasks_ok) return false;
  bool ok = true;
  if (!parallel_top_) {  // no OpenMP construct per level: a path of rows pays nothing
    for (const int k : top_rows_)
      if (!factorize_row(a, k, forward)) return false;
    return true;
  }
  // The rows above the tasks, stage by stage (analyze): a level's rows concurrently. A path of
  // single-row levels goes in three passes: (1) every row's prefix, its entries in columns below
  // the path (final already), leaving out the updates into the path's columns; (2) those updates;
  // (3) the rest of each row, in order. In (1) and (2) each row reads final entries and writes
  // only its own: concurrently, one slot map per thread. Every entry receives its updates in the
  // same order as row by row, so the result is the same bit for bit.
  const int threads = omp_get_max_threads();
  if (thread_slot_.size() < static_cast<size_t>(threads) * size_) thread_slot_.resize(static_cast<size_t>(threads) * size_);
#pragma omp parallel if (team_)
  for (const Stage& stage : stages_) {
    if (!stage.path) {
#pragma omp for schedule(dynamic, 1) reduction(&& : ok)
      for (int q = stage.begin; q < stage.end; ++q) ok = factorize_row(a, top_rows_[q], forward) && ok;
      continue;
    }
    int* slot = thread_slot_.data() + static_cast<size_t>(omp_get_thread_num()) * size_;
    const int lowest = top_rows_[stage.begin];
    // Rows in runs of path_rows_per_thread: consecutive rows' entries in a column are neighbours in
    // memory (72-byte blocks share cache lines), so rows handed out one by one to alternating
    // threads wrote the same lines from both cores - slower on two threads than on one.
#pragma omp for schedule(dynamic, path_rows_per_thread)
    for (int q = stage.begin; q < stage.end; ++q) {
      const int k = top_rows_[q];
      form_row(a, k, row_start_[k], split_[q], forward, slot, false, lowest, deferred_z_.data() + deferred_start_[q]);
    }
#pragma omp for schedule(dynamic, path_rows_per_thread)
    for (int q = stage.begin; q < stage.end; ++q)
      apply_deferred(a, top_rows_[q], split_[q], lowest, deferred_z_.data() + deferred_start_[q], slot);
    if (stage.dense) {
      if (!factorize_dense_path(a, stage, forward)) ok = false;  // the same on every thread
      continue;
    }
#pragma omp single
    for (int q = stage.begin; q < stage.end && ok; ++q) {
      const int k = top_rows_[q];
      ok = form_row(a, k, split_[q], row_start_[k + 1], forward, slot_.data(), true, std::numeric_limits<int>::max(), nullptr);
    }
  }
  return ok;
}

bool BlockLDLT::factorize_dense_path(BlockMatrix& a, const Stage& stage, double* forward) {
  // After passes (1) and (2) a path row's entries in the path's columns hold A(k, r) less the
  // prefix's updates, and its diagonal block the running D_k (upper triangle): together the
  // Schur complement of everything below the path, which the dense factorisation completes.
  // The path's rows are numbered consecutively (analyze): row r's place in it is r − lowest, and
  // a row's entries from its split on are in the path's own columns.
  const int rows = stage.end - stage.begin, lowest = top_rows_[stage.begin];
#pragma omp single
  {
    dense_.setZero(3 * rows, 3 * rows);
    for (int q = stage.begin; q < stage.end; ++q) {
      const int k = top_rows_[q], i = q - stage.begin;
      dense_.block<3, 3>(3 * i, 3 * i) = a.value[a.column[k]].transpose();  // its lower triangle = the running upper one
      for (int t = split_[q]; t < row_start_[k + 1]; ++t)
        dense_.block<3, 3>(3 * i, 3 * (row_column_[t] - lowest)) = a.value[row_position_[t]];
    }
  }
  if (!dense_ldlt_.factorize(dense_)) return false;
#pragma omp single
  {
  negative_pivots_ += dense_ldlt_.negative_pivots();
  for (int q = stage.begin; q < stage.end; ++q) {
    const int k = top_rows_[q], i = q - stage.begin;
    a.value[a.column[k]] = dense_.block<3, 3>(3 * i, 3 * i);
    for (int t = split_[q]; t < row_start_[k + 1]; ++t)
      a.value[row_position_[t]] = dense_.block<3, 3>(3 * i, 3 * (row_column_[t] - lowest));
    if (forward) {  // y_k −= Σ L(k, r) y_r over the path's columns (the prefix's went in pass (1))
      Eigen::Map<Eigen::Vector3d> yk(forward + 3 * k);
      Eigen::Vector3d sum = yk;
      for (int t = split_[q]; t < row_start_[k + 1]; ++t)
        sum.noalias() -= a.value[row_position_[t]] * Eigen::Map<const Eigen::Vector3d>(forward + 3 * row_column_[t]);
      yk = sum;
    }
  }
  }
  return true;
}

void BlockLDLT::solve_in_place(Eigen::VectorXd& b) const {
  // The factorisation's tasks are whole subtrees: a column of a task reaches only rows of the
  // same task (up to its root, the task's largest row) and rows above all tasks. So each task
  // solves on its own, and the rows above them are done in between, level by level: in the
  // forward pass after the tasks (each row gathering from final columns), in the backward pass
  // before them. The partition depends only on the pattern: bit-identical for any thread count.
  const BlockMatrix& a = *factor_;
  const int tasks = static_cast<int>(task_start_.size()) - 1;
  // L y = b
  util::parallel_for_dynamic(0, tasks, parallel_tasks_, [&](int t) {
    const int root = task_rows_[task_start_[t + 1] - 1];
    for (int q = task_start_[t]; q < task_start_[t + 1]; ++q) {
      const int i = task_rows_[q];
      const Eigen::Vector3d bi = b.segment<3>(3 * i);
      for (int p = a.column[i] + 1; p < a.column[i + 1] && a.row[p] <= root; ++p)
        b.segment<3>(3 * a.row[p]).noalias() -= a.value[p] * bi;
    }
  });
  const int levels = static_cast<int>(level_start_.size()) - 1;
  auto forward = [&](int k) {
    Eigen::Vector3d bk = b.segment<3>(3 * k);
    for (int t = row_start_[k]; t < row_start_[k + 1]; ++t) bk.noalias() -= a.value[row_position_[t]] * b.segment<3>(3 * row_column_[t]);
    b.segment<3>(3 * k) = bk;
  };
  if (!parallel_top_levels_) {
    for (const int k : top_rows_) forward(k);
  } else {
#pragma omp parallel
    for (int l = 0; l < levels; ++l) {
#pragma omp for schedule(dynamic, 1)
      for (int q = level_start_[l]; q < level_start_[l + 1]; ++q) forward(top_rows_[q]);
    }
  }
  finish_solve(b);
}

void BlockLDLT::finish_solve(Eigen::VectorXd& b) const {
  const BlockMatrix& a = *factor_;
  const int tasks = static_cast<int>(task_start_.size()) - 1;
  const int levels = static_cast<int>(level_start_.size()) - 1;
  // D z = y and Lᵀ x = z in one pass: x_i = D_i⁻¹ y_i − Σ L(p, i)ᵀ x_p, a dot product down each
  // column (D_i⁻¹ heads it), the rows above the tasks first.
  auto backward = [&](int i) {
    Eigen::Vector3d xi = a.value[a.column[i]] * b.segment<3>(3 * i);
    for (int p = a.column[i] + 1; p < a.column[i + 1]; ++p) xi.noalias() -= a.value[p].transpose() * b.segment<3>(3 * a.row[p]);
    b.segment<3>(3 * i) = xi;
  };
  if (!parallel_top_levels_) {
    for (auto k = top_rows_.rbegin(); k != top_rows_.rend(); ++k) backward(*k);
  } else {
#pragma omp parallel
    for (int l = levels - 1; l >= 0; --l) {
#pragma omp for schedule(dynamic, 1)
      for (int q = level_start_[l]; q < level_start_[l + 1]; ++q) backward(top_rows_[q]);
    }
  }
  util::parallel_for_dynamic(0, tasks, parallel_tasks_, [&](int t) {
    for (int q = task_start_[t + 1] - 1; q >= task_start_[t]; --q) backward(task_rows_[q]);
  });
}

}  // namespace tsm::solver

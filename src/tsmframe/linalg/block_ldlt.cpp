#include "tsmframe/linalg/block_ldlt.hpp"

#include "tsmframe/util/parallel_for.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <omp.h>

namespace tsm::linalg {
namespace {

constexpr int path_rows_per_thread = 8;      // a thread's run of consecutive path rows (false sharing)

// The factorisation's 3×3 block products are arithmetic-bound (a lattice frame's top separator):
// on x86-64 they are also compiled for AVX2 + FMA, picked at load time where the CPU has them
// (GCC function multi-versioning; the baseline build still runs anywhere). Results then depend on
// the CPU's instruction set in their last bits (FMA rounds once), never on the number of threads.
// Clang builds the baseline only.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__linux__)
#define TSM_BLOCK_KERNEL __attribute__((target_clones("default", "arch=x86-64-v3")))
#else
#define TSM_BLOCK_KERNEL
#endif

/// C −= Z Bᵀ for 3×3 blocks (column-major, 9 doubles each) with Z fixed: the factorisation's
/// inner update, streaming B down a column. Z is spread over lanes once, so that each update is
/// two 4-wide and one scalar multiply-add chain on C's entries 0–3, 4–7 and 8, with B's columns
/// permuted into place (faster than Eigen's 3×3 product on blocks in cache). Every load and store stays
/// inside its own block (a neighbouring block may be another thread's). Entry by entry it is the
/// same arithmetic as (Z Bᵀ)(r, c) = Z(r, 0) B(c, 0) + Z(r, 1) B(c, 1) + Z(r, 2) B(c, 2).
class RankThreeUpdate {
 public:
  using Lanes = double __attribute__((vector_size(32), aligned(8)));
#if defined(__clang__)
// Lanes a, b, c, d of v, in that order: GCC's __builtin_shuffle is clang's __builtin_shufflevector.
#define TSM_PICK(v, a, b, c, d) __builtin_shufflevector(v, v, a, b, c, d)
#else
  using Picks = long __attribute__((vector_size(32)));
#define TSM_PICK(v, a, b, c, d) __builtin_shuffle(v, Picks{a, b, c, d})
#endif
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
    low -= first_[0] * TSM_PICK(b0, 0, 0, 0, 1) + first_[1] * TSM_PICK(b1, 0, 0, 0, 1) + first_[2] * TSM_PICK(b2, 1, 1, 1, 2);
    high -= second_[0] * TSM_PICK(b0, 1, 1, 2, 2) + second_[1] * TSM_PICK(b1, 1, 1, 2, 2) + second_[2] * TSM_PICK(b2, 2, 2, 3, 3);
    c[8] -= last_[0] * b[2] + last_[1] * b[5] + last_[2] * b[8];
    __builtin_memcpy(c, &low, sizeof low);
    __builtin_memcpy(c + 4, &high, sizeof high);
  }

 private:
  Lanes first_[3], second_[3];
  double last_[3];
};
#undef TSM_PICK

}  // namespace

void BlockLDLT::analyze(const BlockMatrix& a) {
  size_ = a.size;
  analyze_rows(a, rows_);
  if (rows_.schedule.parallel_top) deferred_z_.resize(rows_.schedule.deferred);  // the path rows' running sums, pass (1) to (2)
  else std::vector<Block>().swap(deferred_z_);
  dense_.resize(0, 0);
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
  const int first = rows_.start[k], last = rows_.start[k + 1];
  for (int t = first; t < last; ++t) slot[rows_.column[t]] = rows_.position[t];
  if (t_begin == first && !rows_.fill.empty())  // the row's first call: its fill starts at zero (no entry of A)
    for (int t = first; t < last; ++t)
      if (rows_.fill[t]) a.value[rows_.position[t]].setZero();
  // D_k is symmetric: only its upper triangle is formed (d00 d01 d02 d11 d12 d22).
  Block& diagonal = a.value[a.column[k]];
  double d00 = diagonal(0, 0), d01 = diagonal(0, 1), d02 = diagonal(0, 2), d11 = diagonal(1, 1), d12 = diagonal(1, 2),
         d22 = diagonal(2, 2);
  if (guard_inertia_ && t_begin == first) original_diagonal_[k] = {d00, d11, d22};  // what the pivot is measured against
  for (int t = t_begin; t < t_end; ++t) {
    const int i = rows_.column[t];
    Block& z = a.value[rows_.position[t]];
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
    const int end = rows_.position[t];
    const RankThreeUpdate update(z);
    for (int p = a.column[i] + 1; p < end && a.row[p] < defer_from; ++p) update.subtract_from(a.value[slot[a.row[p]]], a.value[p]);
    if (deferred) deferred[t - t_begin] = z;
    z = lki;
  }
  if (forward) {  // y_k = b_k − Σ L(k, i) y_i, the rows i < k being final
    Eigen::Map<Eigen::Vector3d> yk(forward + 3 * k);
    Eigen::Vector3d sum = yk;
    for (int t = t_begin; t < t_end; ++t)
      sum.noalias() -= a.value[rows_.position[t]] * Eigen::Map<const Eigen::Vector3d>(forward + 3 * rows_.column[t]);
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
  if (negatives > 0) thread_inertia_[omp_get_thread_num()].inertia.negative += negatives;  // each thread its own line
  if (guard_inertia_ && !inverse_clear(diagonal, original_diagonal_[k]))
    check_pivot(d, original_diagonal_[k], k, thread_inertia_[omp_get_thread_num()].inertia);
  return true;
}

TSM_BLOCK_KERNEL void BlockLDLT::apply_deferred(BlockMatrix& a, int k, int t_end, int defer_from, const Block* deferred, int* slot) const {
  const int first = rows_.start[k], last = rows_.start[k + 1];
  for (int t = first; t < last; ++t) slot[rows_.column[t]] = rows_.position[t];
  for (int t = first; t < t_end; ++t) {
    const int i = rows_.column[t], end = rows_.position[t];
    int p = end;  // rows ascending: the deferred ones (≥ defer_from) end the stretch above (k, i)
    while (p > a.column[i] + 1 && a.row[p - 1] >= defer_from) --p;
    const RankThreeUpdate update(deferred[t - first]);
    for (; p < end; ++p) update.subtract_from(a.value[slot[a.row[p]]], a.value[p]);
  }
}

bool BlockLDLT::factorize_row(BlockMatrix& a, int k, double* forward) {
  return form_row(a, k, rows_.start[k], rows_.start[k + 1], forward, rows_.slot.data(), true, std::numeric_limits<int>::max(), nullptr);
}

bool BlockLDLT::factorize(BlockMatrix& a, Eigen::VectorXd* forward_rhs) {
  factor_ = &a;
  dense_inertia_ = {};
  thread_inertia_.assign(omp_get_max_threads(), {});
  if (guard_inertia_) original_diagonal_.resize(size_);
  double* forward = forward_rhs ? forward_rhs->data() : nullptr;
  // Rows of one subtree touch only that subtree's columns (their patterns are descendants):
  // the tasks run concurrently, each in ascending order.
  const int tasks = static_cast<int>(rows_.schedule.task_start.size()) - 1;
  const bool tasks_ok = util::parallel_all_dynamic(0, tasks, rows_.schedule.parallel_tasks, [&](int t) {
    for (int r = rows_.schedule.task_start[t]; r < rows_.schedule.task_start[t + 1]; ++r)
      if (!factorize_row(a, rows_.schedule.task_rows[r], forward)) return false;
    return true;
  });
  if (!tasks_ok) return false;
  bool ok = true;
  if (!rows_.schedule.parallel_top) {  // no OpenMP construct per level: a path of rows pays nothing
    for (const int k : rows_.schedule.top_rows)
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
#pragma omp parallel if (rows_.schedule.team)
  for (const BlockLDLTSchedule::Stage& stage : rows_.schedule.stages) {
    if (!stage.path) {
#pragma omp for schedule(dynamic, 1) reduction(&& : ok)
      for (int q = stage.begin; q < stage.end; ++q) ok = factorize_row(a, rows_.schedule.top_rows[q], forward) && ok;
      continue;
    }
    int* slot = thread_slot_.data() + static_cast<size_t>(omp_get_thread_num()) * size_;
    const int lowest = rows_.schedule.top_rows[stage.begin];
    // Rows in runs of path_rows_per_thread: consecutive rows' entries in a column are neighbours in
    // memory (72-byte blocks share cache lines), so rows handed out one by one to alternating
    // threads wrote the same lines from both cores - slower on two threads than on one.
#pragma omp for schedule(dynamic, path_rows_per_thread)
    for (int q = stage.begin; q < stage.end; ++q) {
      const int k = rows_.schedule.top_rows[q];
      form_row(a, k, rows_.start[k], rows_.schedule.split[q], forward, slot, false, lowest, deferred_z_.data() + rows_.schedule.deferred_start[q]);
    }
#pragma omp for schedule(dynamic, path_rows_per_thread)
    for (int q = stage.begin; q < stage.end; ++q)
      apply_deferred(a, rows_.schedule.top_rows[q], rows_.schedule.split[q], lowest, deferred_z_.data() + rows_.schedule.deferred_start[q], slot);
    if (stage.dense) {
      if (!factorize_dense_path(a, stage, forward)) ok = false;  // the same on every thread
      continue;
    }
#pragma omp single
    for (int q = stage.begin; q < stage.end && ok; ++q) {
      const int k = rows_.schedule.top_rows[q];
      ok = form_row(a, k, rows_.schedule.split[q], rows_.start[k + 1], forward, rows_.slot.data(), true, std::numeric_limits<int>::max(), nullptr);
    }
  }
  return ok;
}

bool BlockLDLT::factorize_dense_path(BlockMatrix& a, const BlockLDLTSchedule::Stage& stage, double* forward) {
  // After passes (1) and (2) a path row's entries in the path's columns hold A(k, r) less the
  // prefix's updates, and its diagonal block the running D_k (upper triangle): together the
  // Schur complement of everything below the path, which the dense factorisation completes.
  // The path's rows are numbered consecutively (analyze): row r's place in it is r − lowest, and
  // a row's entries from its split on are in the path's own columns.
  const int rows = stage.end - stage.begin, lowest = rows_.schedule.top_rows[stage.begin];
#pragma omp single
  {
    dense_.setZero(3 * rows, 3 * rows);
    dense_original_.resize(rows);
    for (int q = stage.begin; q < stage.end; ++q) {
      const int k = rows_.schedule.top_rows[q], i = q - stage.begin;
      if (guard_inertia_) dense_original_[i] = original_diagonal_[k];
      dense_.block<3, 3>(3 * i, 3 * i) = a.value[a.column[k]].transpose();  // its lower triangle = the running upper one
      for (int t = rows_.schedule.split[q]; t < rows_.start[k + 1]; ++t)
        dense_.block<3, 3>(3 * i, 3 * (rows_.column[t] - lowest)) = a.value[rows_.position[t]];
    }
  }
  if (!dense_ldlt_.factorize(dense_, guard_inertia_ ? dense_original_.data() : nullptr)) return false;
#pragma omp single
  {
  Inertia dense = dense_ldlt_.inertia();
  if (dense.row >= 0) dense.row = rows_.schedule.top_rows[stage.begin + dense.row];
  dense_inertia_.add(dense);
  for (int q = stage.begin; q < stage.end; ++q) {
    const int k = rows_.schedule.top_rows[q], i = q - stage.begin;
    a.value[a.column[k]] = dense_.block<3, 3>(3 * i, 3 * i);
    for (int t = rows_.schedule.split[q]; t < rows_.start[k + 1]; ++t)
      a.value[rows_.position[t]] = dense_.block<3, 3>(3 * i, 3 * (rows_.column[t] - lowest));
    if (forward) {  // y_k −= Σ L(k, r) y_r over the path's columns (the prefix's went in pass (1))
      Eigen::Map<Eigen::Vector3d> yk(forward + 3 * k);
      Eigen::Vector3d sum = yk;
      for (int t = rows_.schedule.split[q]; t < rows_.start[k + 1]; ++t)
        sum.noalias() -= a.value[rows_.position[t]] * Eigen::Map<const Eigen::Vector3d>(forward + 3 * rows_.column[t]);
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
  const int tasks = static_cast<int>(rows_.schedule.task_start.size()) - 1;
  // L y = b
  util::parallel_for_dynamic(0, tasks, rows_.schedule.parallel_tasks, [&](int t) {
    const int root = rows_.schedule.task_rows[rows_.schedule.task_start[t + 1] - 1];
    for (int q = rows_.schedule.task_start[t]; q < rows_.schedule.task_start[t + 1]; ++q) {
      const int i = rows_.schedule.task_rows[q];
      const Eigen::Vector3d bi = b.segment<3>(3 * i);
      for (int p = a.column[i] + 1; p < a.column[i + 1] && a.row[p] <= root; ++p)
        b.segment<3>(3 * a.row[p]).noalias() -= a.value[p] * bi;
    }
  });
  const int levels = static_cast<int>(rows_.schedule.level_start.size()) - 1;
  auto forward = [&](int k) {
    Eigen::Vector3d bk = b.segment<3>(3 * k);
    for (int t = rows_.start[k]; t < rows_.start[k + 1]; ++t) bk.noalias() -= a.value[rows_.position[t]] * b.segment<3>(3 * rows_.column[t]);
    b.segment<3>(3 * k) = bk;
  };
  if (!rows_.schedule.parallel_top_levels) {
    for (const int k : rows_.schedule.top_rows) forward(k);
  } else {
#pragma omp parallel
    for (int l = 0; l < levels; ++l) {
#pragma omp for schedule(dynamic, 1)
      for (int q = rows_.schedule.level_start[l]; q < rows_.schedule.level_start[l + 1]; ++q) forward(rows_.schedule.top_rows[q]);
    }
  }
  finish_solve(b);
}

void BlockLDLT::finish_solve(Eigen::VectorXd& b) const {
  const BlockMatrix& a = *factor_;
  const int tasks = static_cast<int>(rows_.schedule.task_start.size()) - 1;
  const int levels = static_cast<int>(rows_.schedule.level_start.size()) - 1;
  // D z = y and Lᵀ x = z in one pass: x_i = D_i⁻¹ y_i − Σ L(p, i)ᵀ x_p, a dot product down each
  // column (D_i⁻¹ heads it), the rows above the tasks first.
  auto backward = [&](int i) {
    Eigen::Vector3d xi = a.value[a.column[i]] * b.segment<3>(3 * i);
    for (int p = a.column[i] + 1; p < a.column[i + 1]; ++p) xi.noalias() -= a.value[p].transpose() * b.segment<3>(3 * a.row[p]);
    b.segment<3>(3 * i) = xi;
  };
  if (!rows_.schedule.parallel_top_levels) {
    for (auto k = rows_.schedule.top_rows.rbegin(); k != rows_.schedule.top_rows.rend(); ++k) backward(*k);
  } else {
#pragma omp parallel
    for (int l = levels - 1; l >= 0; --l) {
#pragma omp for schedule(dynamic, 1)
      for (int q = rows_.schedule.level_start[l]; q < rows_.schedule.level_start[l + 1]; ++q) backward(rows_.schedule.top_rows[q]);
    }
  }
  util::parallel_for_dynamic(0, tasks, rows_.schedule.parallel_tasks, [&](int t) {
    for (int q = rows_.schedule.task_start[t + 1] - 1; q >= rows_.schedule.task_start[t]; --q) backward(rows_.schedule.task_rows[q]);
  });
}

}  // namespace tsm::linalg

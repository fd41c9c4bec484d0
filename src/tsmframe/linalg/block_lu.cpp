#include "tsmframe/linalg/block_lu.hpp"

#include <Eigen/LU>
#include <cmath>

#include "tsmframe/util/parallel_for.hpp"

namespace tsm::linalg {

void BlockLU::analyze(const BlockMatrix& a) {
  size_ = a.size;
  analyze_rows(a, rows_);
}

bool BlockLU::factorize_row(BlockMatrix& a, std::vector<Block>& upper, int k) {
  // Row k's entries (k, i), i ascending, hold A(k, i) and, in `upper`, A(i, k)ᵀ; they serve as
  // the running sums zl = A(k, i) − Σ_j L(k, j) D_j U(j, i) and zu = A(i, k)ᵀ − Σ_j U(j, k)ᵀ
  // D_jᵀ L(i, j)ᵀ, and become L(k, i) = zl D_i⁻¹ and U(i, k)ᵀ = zu D_i⁻ᵀ. The diagonal block
  // becomes D_k⁻¹, D_k = A(k, k) − Σ_i L(k, i) D_i U(i, k).
  const int first = rows_.start[k], last = rows_.start[k + 1];
  int* slot = rows_.slot.data();
  for (int t = first; t < last; ++t) slot[rows_.column[t]] = rows_.position[t];
  if (!rows_.fill.empty())
    for (int t = first; t < last; ++t)
      if (rows_.fill[t]) a.value[rows_.position[t]].setZero(), upper[rows_.position[t]].setZero();
  Block& diagonal = a.value[a.column[k]];
  Block d = diagonal;
  for (int t = first; t < last; ++t) {
    const int i = rows_.column[t], p = rows_.position[t];
    Block& zl = a.value[p];
    Block& zu = upper[p];
    const Block& inverse = a.value[a.column[i]];  // D_i⁻¹
    const Block lki = zl * inverse;
    const Block uik = zu * inverse.transpose();
    d.noalias() -= lki * zu.transpose();
    // Column i's rows r (i < r < k) update the running sums (k, r) of both triangles.
    for (int q = a.column[i] + 1; q < p; ++q) {
      const int r = slot[a.row[q]];
      a.value[r].noalias() -= zl * upper[q].transpose();
      upper[r].noalias() -= zu * a.value[q].transpose();
    }
    zl = lki;
    zu = uik;
  }
  if (!d.allFinite()) return false;
  Block inverse;
  bool invertible = false;
  d.computeInverseWithCheck(inverse, invertible, 0.0);
  if (!invertible || !inverse.allFinite()) return false;
  diagonal = inverse;
  return true;
}

bool BlockLU::factorize(BlockMatrix& a, std::vector<Block>& upper) {
  lower_ = &a;
  upper_ = &upper;
  // Rows of one subtree touch only that subtree's columns: the tasks run concurrently, each in
  // ascending order; the rows above them follow in order.
  const int tasks = rows_.schedule.task_count();
  const bool tasks_ok = util::parallel_all_dynamic(0, tasks, rows_.schedule.parallel_tasks, [&](int t) {
    for (int r = rows_.schedule.task_start[t]; r < rows_.schedule.task_start[t + 1]; ++r)
      if (!factorize_row(a, upper, rows_.schedule.task_rows[r])) return false;
    return true;
  });
  if (!tasks_ok) return false;
  for (const int k : rows_.schedule.top_rows)
    if (!factorize_row(a, upper, k)) return false;
  return true;
}

void BlockLU::solve_in_place(Eigen::VectorXd& b) const {
  const BlockMatrix& a = *lower_;
  const std::vector<Block>& upper = *upper_;
  // L y = b, by columns (the order of the columns is the blocks').
  for (int c = 0; c < size_; ++c) {
    const Eigen::Vector3d bc = b.segment<3>(3 * c);
    for (int p = a.column[c] + 1; p < a.column[c + 1]; ++p) b.segment<3>(3 * a.row[p]).noalias() -= a.value[p] * bc;
  }
  // D z = y and U x = z: x_c = D_c⁻¹ y_c − Σ U(c, r) x_r, U(c, r) = (Uᵀ at the entry (r, c))ᵀ.
  for (int c = size_ - 1; c >= 0; --c) {
    Eigen::Vector3d xc = a.value[a.column[c]] * b.segment<3>(3 * c);
    for (int p = a.column[c] + 1; p < a.column[c + 1]; ++p) xc.noalias() -= upper[p].transpose() * b.segment<3>(3 * a.row[p]);
    b.segment<3>(3 * c) = xc;
  }
}

}  // namespace tsm::linalg

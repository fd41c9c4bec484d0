#include "tsmframe/solver/block_ldlt.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace tsm::solver {
namespace {

/// Blocks k < j on the path from each nonzero A(i, j) up the elimination tree (the pattern of
/// row j of L), written to stack[top .. size) in a topological order; returns top (cs_ereach).
int reach(const BlockMatrix& a, int j, const std::vector<int>& parent, std::vector<int>& flag,
          std::vector<int>& stack) {
  const int n = a.size;
  int top = n;
  flag[j] = j;
  for (int p = a.column[j]; p < a.column[j + 1]; ++p) {
    int i = a.row[p];
    if (i >= j) continue;
    int len = 0;
    for (; flag[i] != j; i = parent[i]) {
      stack[len++] = i;  // the path goes to the front of stack (its tail is not yet used)
      flag[i] = j;
    }
    while (len > 0) stack[--top] = stack[--len];
  }
  return top;
}

}  // namespace

void BlockLDLT::analyze(const BlockMatrix& a) {
  const int n = size_ = a.size;
  // Elimination tree (Liu's algorithm with path compression, cs_etree on the upper triangle).
  parent_.assign(n, -1);
  std::vector<int> ancestor(n, -1);
  for (int k = 0; k < n; ++k) {
    for (int p = a.column[k]; p < a.column[k + 1]; ++p) {
      for (int i = a.row[p]; i != -1 && i < k;) {
        const int next = ancestor[i];
        ancestor[i] = k;
        if (next == -1) {
          parent_[i] = k;
          break;
        }
        i = next;
      }
    }
  }
  // Row k of L is the reach of column k: kept, in topological order, for every factorisation.
  std::vector<int> flag(n, -1), stack(n, 0), count(n, 0);
  row_start_.assign(1, 0);
  row_pattern_.clear();
  for (int k = 0; k < n; ++k) {
    const int top = reach(a, k, parent_, flag, stack);
    for (int t = top; t < n; ++t) {
      ++count[stack[t]];
      row_pattern_.push_back(stack[t]);
    }
    row_start_.push_back(static_cast<int>(row_pattern_.size()));
  }
  row_pattern_.shrink_to_fit();
  l_column_.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) l_column_[i + 1] = l_column_[i] + count[i];
  l_row_.assign(l_column_[n], 0);
  l_value_.resize(l_column_[n]);
  d_inverse_.resize(n);
  fill_.resize(n);
  slot_.assign(n, -1);
  longest_row_ = 0;
  for (int k = 0; k < n; ++k) longest_row_ = std::max(longest_row_, row_start_[k + 1] - row_start_[k]);

  // Tasks: the largest subtrees of at most n / 16 blocks (parents come after children, so one
  // ascending pass sums subtree sizes and one descending pass hands every block to its task).
  std::vector<int> size(n, 1), task(n, -1);
  for (int k = 0; k < n; ++k)
    if (parent_[k] >= 0) size[parent_[k]] += size[k];
  const int limit = std::max(1, n / 16);
  int tasks = 0;
  for (int k = n - 1; k >= 0; --k) {
    const int p = parent_[k];
    if (p >= 0 && task[p] >= 0) task[k] = task[p];
    else if (size[k] <= limit && size[k] >= 64) task[k] = tasks++;
  }
  task_start_.assign(tasks + 1, 0);
  for (int k = 0; k < n; ++k)
    if (task[k] >= 0) ++task_start_[task[k] + 1];
  for (int t = 0; t < tasks; ++t) task_start_[t + 1] += task_start_[t];
  task_rows_.resize(task_start_[tasks]);
  top_rows_.clear();
  std::vector<int> next(task_start_.begin(), task_start_.end() - 1);
  for (int k = 0; k < n; ++k) {
    if (task[k] >= 0) task_rows_[next[task[k]]++] = k;
    else top_rows_.push_back(k);
  }
}

bool BlockLDLT::factorize_row(const BlockMatrix& a, int k, Block* work) {
  // The row's pattern gets places 0 … len−1 in `work`, zeroed; then the upper column k of A is
  // scattered in (its rows above k are all in the pattern).
  const int first = row_start_[k], len = row_start_[k + 1] - first;
  for (int t = 0; t < len; ++t) {
    slot_[row_pattern_[first + t]] = t;
    work[t].setZero();
  }
  // D_k is symmetric: only its upper triangle is formed (d00 d01 d02 d11 d12 d22).
  double d00 = 0, d01 = 0, d02 = 0, d11 = 0, d12 = 0, d22 = 0;
  for (int p = a.column[k]; p < a.column[k + 1]; ++p) {
    if (a.row[p] == k) {
      const Block& b = a.value[p];
      d00 = b(0, 0), d01 = b(0, 1), d02 = b(0, 2), d11 = b(1, 1), d12 = b(1, 2), d22 = b(2, 2);
    } else {
      work[slot_[a.row[p]]] = a.value[p];
    }
  }
  for (int t = 0; t < len; ++t) {
    const int i = row_pattern_[first + t];
    const Block& y = work[t];  // = D_i L(k, i)ᵀ once the earlier columns are subtracted
    Block lki;
    lki.noalias() = y.transpose() * d_inverse_[i];  // L(k, i) = yᵀ D_i⁻¹
    // D_k −= L(k, i) y (= yᵀ D_i⁻¹ y, symmetric): the upper triangle only.
    d00 -= lki.row(0).dot(y.col(0));
    d01 -= lki.row(0).dot(y.col(1));
    d02 -= lki.row(0).dot(y.col(2));
    d11 -= lki.row(1).dot(y.col(1));
    d12 -= lki.row(1).dot(y.col(2));
    d22 -= lki.row(2).dot(y.col(2));
    for (int p = l_column_[i]; p < fill_[i]; ++p) work[slot_[l_row_[p]]].noalias() -= l_value_[p] * y;
    l_row_[fill_[i]] = k;
    l_value_[fill_[i]++] = lki;
  }
  // D_k⁻¹ by cofactors of the symmetric block.
  const double c00 = d11 * d22 - d12 * d12, c01 = d02 * d12 - d01 * d22, c02 = d01 * d12 - d02 * d11;
  const double c11 = d00 * d22 - d02 * d02, c12 = d01 * d02 - d00 * d12, c22 = d00 * d11 - d01 * d01;
  const double det = d00 * c00 + d01 * c01 + d02 * c02;
  if (!(det != 0.0) || !std::isfinite(det)) return false;
  const double r = 1.0 / det;
  Block& inverse = d_inverse_[k];
  inverse << c00 * r, c01 * r, c02 * r,  //
      c01 * r, c11 * r, c12 * r,         //
      c02 * r, c12 * r, c22 * r;
  return std::isfinite(r) && std::isfinite(c00 * r) && std::isfinite(c01 * r) && std::isfinite(c02 * r) &&
         std::isfinite(c11 * r) && std::isfinite(c12 * r) && std::isfinite(c22 * r);
}

bool BlockLDLT::factorize(const BlockMatrix& a) {
  std::copy(l_column_.begin(), l_column_.end() - 1, fill_.begin());
  // Rows of one subtree touch only that subtree's columns and workspace (their patterns are
  // descendants): the tasks run concurrently, each in ascending order.
  const int tasks = static_cast<int>(task_start_.size()) - 1;
  bool ok = true;
#pragma omp parallel reduction(&& : ok) if (tasks > 1)
  {
    std::vector<Block> work(longest_row_);
#pragma omp for schedule(dynamic, 1)
    for (int t = 0; t < tasks; ++t)
      for (int r = task_start_[t]; r < task_start_[t + 1] && ok; ++r) ok = factorize_row(a, task_rows_[r], work.data());
  }
  if (!ok) return false;
  std::vector<Block> work(longest_row_);
  for (const int k : top_rows_)
    if (!factorize_row(a, k, work.data())) return false;
  return true;
}

void BlockLDLT::solve_in_place(Eigen::VectorXd& b) const {
  const int n = size_;
  for (int i = 0; i < n; ++i) {  // L y = b
    const Eigen::Vector3d bi = b.segment<3>(3 * i);
    for (int p = l_column_[i]; p < l_column_[i + 1]; ++p) b.segment<3>(3 * l_row_[p]).noalias() -= l_value_[p] * bi;
  }
  for (int i = 0; i < n; ++i) b.segment<3>(3 * i) = d_inverse_[i] * b.segment<3>(3 * i).eval();  // D z = y
  for (int i = n - 1; i >= 0; --i) {  // Lᵀ x = z
    Eigen::Vector3d bi = b.segment<3>(3 * i);
    for (int p = l_column_[i]; p < l_column_[i + 1]; ++p) bi.noalias() -= l_value_[p].transpose() * b.segment<3>(3 * l_row_[p]);
    b.segment<3>(3 * i) = bi;
  }
}

}  // namespace tsm::solver

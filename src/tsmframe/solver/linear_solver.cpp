#include "tsmframe/solver/linear_solver.hpp"

namespace tsm::solver {

void LinearSolver::analyze(const assembly::DofMap& dofs, const BlockMatrix& matrix) {
  dofs_ = &dofs;
  padded_.resize(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) {
    const int dof = dofs.dof(eq);
    padded_[eq] = dofs_per_node * dofs.block(dof / dofs_per_node) + dof % dofs_per_node;
  }
  padded_size_ = dofs_per_node * dofs.block_count();
  ldlt_.analyze(matrix);
}

bool LinearSolver::factorize(const BlockMatrix& matrix, const std::vector<DenseTerm>& extra) {
  general_ = !extra.empty();
  if (general_) return factorize_general(matrix, extra);
  return ldlt_.factorize(matrix);
}

bool LinearSolver::factorize_general(const BlockMatrix& matrix, const std::vector<DenseTerm>& extra) {
  const assembly::DofMap& dofs = *dofs_;
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(2 * 9 * matrix.value.size() + 81 * extra.size());
  auto equation = [&](int block, int d) { return dofs.equation(dofs_per_node * dofs.block_node(block) + d); };
  for (int c = 0; c < matrix.size; ++c) {
    for (int p = matrix.column[c]; p < matrix.column[c + 1]; ++p) {
      const int r = matrix.row[p];
      const Block& b = matrix.value[p];
      for (int a = 0; a < dofs_per_node; ++a) {
        const int row = equation(r, a);
        if (row < 0) continue;
        for (int d = 0; d < dofs_per_node; ++d) {
          const int col = equation(c, d);
          if (col < 0) continue;
          entries.emplace_back(row, col, b(a, d));
          if (r != c) entries.emplace_back(col, row, b(a, d));
        }
      }
    }
  }
  for (const DenseTerm& t : extra)
    for (int a = 0; a < 9; ++a) {
      if (t.equation[a] < 0) continue;
      for (int b = 0; b < 9; ++b)
        if (t.equation[b] >= 0) entries.emplace_back(t.equation[a], t.equation[b], t.value(a, b));
    }
  const int n = dofs.free_count();
  general_matrix_.resize(n, n);
  general_matrix_.setFromTriplets(entries.begin(), entries.end());
  if (!general_matrix_.coeffs().allFinite()) return false;
  lu_ = std::make_unique<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>>();
  lu_->analyzePattern(general_matrix_);
  lu_->factorize(general_matrix_);
  return lu_->info() == Eigen::Success;
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& rhs) const {
  if (general_) return lu_->solve(rhs);
  Eigen::VectorXd padded = Eigen::VectorXd::Zero(padded_size_);
  for (Eigen::Index eq = 0; eq < rhs.size(); ++eq) padded[padded_[eq]] = rhs[eq];
  ldlt_.solve_in_place(padded);
  Eigen::VectorXd x(rhs.size());
  for (Eigen::Index eq = 0; eq < rhs.size(); ++eq) x[eq] = padded[padded_[eq]];
  return x;
}

}  // namespace tsm::solver

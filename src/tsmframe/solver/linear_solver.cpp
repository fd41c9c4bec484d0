#include "tsmframe/solver/linear_solver.hpp"

namespace tsm::solver {

void LinearSolver::analyze(const assembly::DofMap& dofs, const BlockMatrix& matrix) {
  padded_.resize(dofs.free_count());
  for (int eq = 0; eq < dofs.free_count(); ++eq) {
    const int dof = dofs.dof(eq);
    padded_[eq] = dofs_per_node * dofs.block(dof / dofs_per_node) + dof % dofs_per_node;
  }
  padded_size_ = dofs_per_node * dofs.block_count();
  ldlt_.analyze(matrix);
}

bool LinearSolver::factorize(const BlockMatrix& matrix) { return ldlt_.factorize(matrix); }

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd padded = Eigen::VectorXd::Zero(padded_size_);
  for (Eigen::Index eq = 0; eq < rhs.size(); ++eq) padded[padded_[eq]] = rhs[eq];
  ldlt_.solve_in_place(padded);
  Eigen::VectorXd x(rhs.size());
  for (Eigen::Index eq = 0; eq < rhs.size(); ++eq) x[eq] = padded[padded_[eq]];
  return x;
}

}  // namespace tsm::solver

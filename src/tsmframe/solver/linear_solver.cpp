#include "tsmframe/solver/linear_solver.hpp"

namespace tsm::solver {

void LinearSolver::analyze(const assembly::SparseMatrix& matrix) { ldlt_.analyzePattern(matrix); }

bool LinearSolver::factorize(const assembly::SparseMatrix& matrix) {
  ldlt_.factorize(matrix);
  if (ldlt_.info() != Eigen::Success) return false;
  const Eigen::VectorXd& pivots = ldlt_.vectorD();
  return pivots.allFinite() && (pivots.array() != 0.0).all();
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& rhs) const { return ldlt_.solve(rhs); }

}  // namespace tsm::solver

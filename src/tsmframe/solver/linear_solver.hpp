#pragma once
// Sparse direct solver for K_ff δD = R. The symbolic analysis (fill-reducing ordering) is done
// once per sparsity pattern; each Newton iteration only refactorises.

#include <Eigen/SparseCholesky>

#include "tsmframe/assembly/global_system.hpp"

namespace tsm::solver {

class LinearSolver {
 public:
  /// Symbolic analysis of the pattern of `matrix` (values ignored).
  void analyze(const assembly::SparseMatrix& matrix);
  /// Numeric factorisation; false if a pivot is zero or not finite.
  bool factorize(const assembly::SparseMatrix& matrix);
  /// Solves with the last factorisation.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

 private:
  Eigen::SimplicialLDLT<assembly::SparseMatrix, Eigen::Lower> ldlt_;
};

}  // namespace tsm::solver

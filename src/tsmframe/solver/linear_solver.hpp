#pragma once
// The linear solver of the Newton iteration: K_ff δD = R with the node-block LDLᵀ (block_ldlt).
// Vectors are over the free equations; the solver pads them to whole node blocks.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/solver/block_ldlt.hpp"

namespace tsm::solver {

class LinearSolver {
 public:
  /// Symbolic analysis of the tangent's block pattern (values ignored); done once.
  void analyze(const assembly::DofMap& dofs, const BlockMatrix& matrix);
  /// Numeric factorisation; false if a pivot block is singular or not finite.
  bool factorize(const BlockMatrix& matrix);
  /// Solves with the last factorisation.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

 private:
  BlockLDLT ldlt_;
  std::vector<int> padded_;  ///< per free equation: its place in the block-padded vector
  int padded_size_ = 0;
};

}  // namespace tsm::solver

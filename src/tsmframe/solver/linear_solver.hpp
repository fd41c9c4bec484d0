#pragma once
// The linear solver of the Newton iteration: K_ff δD = R. The symmetric tangent of beams alone
// goes to the node-block LDLᵀ (block_ldlt); while contact elements are active their
// non-symmetric terms join it and the whole K_ff goes to Eigen's SparseLU (COLAMD ordering).
// Vectors are over the free equations.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <array>
#include <memory>
#include <vector>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/solver/block_ldlt.hpp"

namespace tsm::solver {

/// A dense element matrix over up to 9 global dofs (a contact element), possibly non-symmetric.
struct DenseTerm {
  std::array<int, 9> equation{};         ///< free equation of each row/column, −1 if constrained
  Eigen::Matrix<double, 9, 9> value;
};

class LinearSolver {
 public:
  /// Symbolic analysis of the tangent's block pattern (values ignored); done once.
  void analyze(const assembly::DofMap& dofs, const BlockMatrix& matrix);
  /// Numeric factorisation of `matrix` plus `extra` (contact elements); false if singular or
  /// not finite.
  bool factorize(const BlockMatrix& matrix, const std::vector<DenseTerm>& extra = {});
  /// Solves with the last factorisation.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

 private:
  bool factorize_general(const BlockMatrix& matrix, const std::vector<DenseTerm>& extra);

  BlockLDLT ldlt_;
  const assembly::DofMap* dofs_ = nullptr;
  bool general_ = false;  ///< the last factorisation is the SparseLU one
  Eigen::SparseMatrix<double> general_matrix_;
  std::unique_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>>> lu_;
  std::vector<int> padded_;  ///< per free equation: its place in the block-padded vector
  int padded_size_ = 0;
};

}  // namespace tsm::solver

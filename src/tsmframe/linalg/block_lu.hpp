#pragma once
// Sparse LU factorisation A = L D U over 3×3 node blocks, without pivoting, for a tangent whose
// pattern is symmetric but whose values are not: the TSM tangent with the contacts' sliding
// terms u vᵀ added (each lives on its contact element's nodes, whose blocks the tangent has).
// It is the block LDLᵀ (block_ldlt) with a second triangle: the matrix's lower triangle by
// columns (BlockMatrix, its pattern holding its fill) is overwritten by L below the diagonal and
// D⁻¹ on it, and `upper` — one block per entry, A(c, r)ᵀ at the entry (r, c) — by Uᵀ. The
// diagonal blocks are whole (not symmetric). Up-looking as the LDLᵀ: row k of L and column k
// of U from the finished rows above, the independent subtrees of the elimination tree as
// parallel tasks (BlockLDLTSchedule), every row with the same arithmetic in the same order
// whatever the number of threads.

#include <Eigen/Core>
#include <vector>

#include "tsmframe/linalg/block_ldlt_schedule.hpp"
#include "tsmframe/linalg/block_matrix.hpp"

namespace tsm::linalg {

class BlockLU {
 public:
  /// The elimination tree and the rows of the lower triangle from the pattern of `matrix`, which
  /// must hold its fill (add_fill).
  void analyze(const BlockMatrix& matrix);
  /// Numeric factorisation in place: `matrix` receives L and D⁻¹, `upper` (matrix's entries'
  /// transposed partners) Uᵀ; false if a pivot block is singular or not finite.
  bool factorize(BlockMatrix& matrix, std::vector<Block>& upper);
  /// Solves A x = b in place with the last factorisation; b has 3 entries per block.
  void solve_in_place(Eigen::VectorXd& b) const;

 private:
  int size_ = 0;
  FactorRows rows_;  ///< the filled lower triangle by rows, the slot map (tasks own disjoint columns), the schedule
  const BlockMatrix* lower_ = nullptr;
  const std::vector<Block>* upper_ = nullptr;

  bool factorize_row(BlockMatrix& a, std::vector<Block>& upper, int k);
};

}  // namespace tsm::linalg

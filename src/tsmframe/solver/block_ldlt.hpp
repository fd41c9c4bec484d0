#pragma once
// Sparse LDLᵀ factorisation over 3×3 node blocks, for the symmetric TSM tangent.
//
// Frames are node-blocked by nature (every element couples two nodes' (u, v, θ)), so working
// on dense 3×3 blocks instead of scalars removes most of a scalar sparse factorisation's index
// bookkeeping. The blocks are numbered in a fill-reducing order chosen once (DofMap); the
// elimination tree and the block pattern of L are computed once per pattern (analyze) and each
// Newton iteration only refactorises (factorize). D is block diagonal with 3×3 symmetric blocks
// inverted exactly, so the factorisation also handles indefinite tangents (past a limit point)
// as long as no 3×3 pivot block is singular. Up-looking algorithm as in CSparse's cs_chol,
// lifted to blocks. The arithmetic order is fixed: results do not depend on threads.
// Independent subtrees of the elimination tree are factorised in parallel (OpenMP).

#include <Eigen/Core>
#include <vector>

namespace tsm::solver {

using Block = Eigen::Matrix3d;

/// Symmetric block-sparse matrix: the upper triangle, block column by block column.
struct BlockMatrix {
  int size = 0;                 ///< number of block rows/columns
  std::vector<int> column;      ///< column c holds entries column[c] .. column[c+1]
  std::vector<int> row;         ///< block row of each entry (≤ c, ascending: diagonal last)
  std::vector<Block> value;     ///< 3×3 block of each entry
};

class BlockLDLT {
 public:
  /// Elimination tree and the pattern of L from the pattern of `matrix`.
  void analyze(const BlockMatrix& matrix);
  /// Numeric factorisation; false if a pivot block is singular or not finite.
  bool factorize(const BlockMatrix& matrix);
  /// Solves A x = b in place; b has 3 entries per block.
  void solve_in_place(Eigen::VectorXd& b) const;

  /// Entries (blocks) of L below the diagonal.
  size_t factor_blocks() const { return l_row_.size(); }

 private:
  int size_ = 0;
  std::vector<int> parent_;        ///< elimination tree
  std::vector<int> l_column_;      ///< column i of L: l_column_[i] .. l_column_[i+1]
  std::vector<int> l_row_;
  std::vector<Block> l_value_;
  std::vector<Block> d_inverse_;   ///< D_i⁻¹
  std::vector<int> row_start_;     ///< row k of L: row_pattern_[row_start_[k] .. row_start_[k+1])
  std::vector<int> row_pattern_;   ///< its columns, in a topological order of the elimination tree
  // Workspace for factorize. Row k touches only the blocks of its own pattern, so its running
  // sums live in a compact buffer of the row's length (one per concurrent task), addressed
  // through slot_ (block → place in the current row; subtrees own disjoint blocks).
  std::vector<int> fill_;
  std::vector<int> slot_;
  int longest_row_ = 0;
  // Parallel factorisation: disjoint subtrees of the elimination tree touch disjoint rows,
  // columns and workspace entries, so they are factorised concurrently; the blocks above them
  // follow serially. Every row is computed with the same arithmetic in the same order whatever
  // the number of threads: results are bit-identical.
  std::vector<int> task_start_;  ///< task t: rows task_rows_[task_start_[t] .. task_start_[t+1]), ascending
  std::vector<int> task_rows_;
  std::vector<int> top_rows_;    ///< rows in no task, ascending

  bool factorize_row(const BlockMatrix& a, int k, Block* work);
};

}  // namespace tsm::solver

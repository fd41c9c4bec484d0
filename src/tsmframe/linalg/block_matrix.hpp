#pragma once
// The tangent's storage: a symmetric matrix of 3×3 node blocks, its lower triangle by columns,
// whose pattern may be extended by the fill of its LDLᵀ factor so that the factor overwrites it
// (block_ldlt). Assembly writes it, the solver factorises it.

#include <Eigen/Core>
#include <vector>

namespace tsm::linalg {

using Block = Eigen::Matrix3d;

/// Symmetric block-sparse matrix: the lower triangle, block column by block column.
struct BlockMatrix {
  int size = 0;                 ///< number of block rows/columns
  std::vector<int> column;      ///< column c holds entries column[c] .. column[c+1]
  std::vector<int> row;         ///< block row of each entry (≥ c, ascending: diagonal first)
  std::vector<Block> value;     ///< 3×3 block of each entry: A(row, c)
  /// Per entry: 1 if add_fill added it (no entry of A). Its value is never read - the
  /// factorisation starts it at zero - so it need not be cleared between factorisations; other
  /// readers of the values skip it (is_fill). Empty: no fill.
  std::vector<unsigned char> fill;
  bool is_fill(int entry) const { return !fill.empty() && fill[entry] != 0; }
};

/// The lower triangle read by rows: row k lists the columns i < k with an entry (k, i),
/// ascending, in column[start[k] .. start[k + 1]), and where each entry is stored (position).
struct BlockRows {
  std::vector<int> start, column, position;
};
BlockRows lower_rows(const BlockMatrix& matrix);

/// A pattern that holds its fill, as the block factorisations (block_ldlt, block_lu) read it:
/// its rows, its elimination tree and which row entries are fill (empty: none).
struct FilledPattern {
  BlockRows rows;
  std::vector<int> parent;               ///< each column's parent in the elimination tree, −1 at a root
  std::vector<unsigned char> row_fill;   ///< per entry of rows: added by add_fill
};
/// The pattern of `matrix`, checked to start each column with its diagonal and to hold its fill
/// (closed under elimination); std::logic_error otherwise.
FilledPattern filled_pattern(const BlockMatrix& matrix);

/// Extends the pattern of `matrix` (every column must hold its diagonal) by the fill of its
/// LDLᵀ factor, so that it can be factorised in place, and marks the added entries (fill); the
/// values become zero.
void add_fill(BlockMatrix& matrix);

}  // namespace tsm::linalg
